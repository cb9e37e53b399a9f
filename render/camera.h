#pragma once
// Pinhole look-at camera shared by the renderers.

#include <Eigen/Core>

namespace weft::render {

struct Camera {
  Eigen::Vector3d eye{2.0, -2.5, 1.2};     // metres
  Eigen::Vector3d target{0.0, 0.0, 0.5};  // metres
  Eigen::Vector3d up{0.0, 0.0, 1.0};
  double fov_y_deg = 40.0;                 // vertical field of view
  double near_m = 0.01, far_m = 100.0;

  Eigen::Matrix4f view_matrix() const;                     // world → camera (OpenGL convention)
  Eigen::Matrix4f projection_matrix(double aspect) const;  // camera → clip (OpenGL convention)
};

}  // namespace weft::render
