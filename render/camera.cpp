// Look-at view and perspective projection matrices, OpenGL conventions: the camera looks down
// its −z axis with +y up; clip space maps near → NDC z = −1 and far → +1.

#include "render/camera.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace weft::render {

Eigen::Matrix4f Camera::view_matrix() const {
  const Eigen::Vector3d forward_unnormalised = target - eye;
  if (!(forward_unnormalised.norm() > 0.0)) {
    throw std::invalid_argument("Camera: eye and target coincide (or are not finite)");
  }
  const Eigen::Vector3d forward = forward_unnormalised.normalized();
  const Eigen::Vector3d side_unnormalised = forward.cross(up);
  if (!(side_unnormalised.norm() > 1e-9 * up.norm()) || !(up.norm() > 0.0)) {
    throw std::invalid_argument("Camera: up is zero or parallel to the view direction");
  }
  const Eigen::Vector3d side = side_unnormalised.normalized();  // camera +x, world units
  const Eigen::Vector3d true_up = side.cross(forward);          // camera +y

  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = side.transpose();
  view.block<1, 3>(1, 0) = true_up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view(0, 3) = -side.dot(eye);
  view(1, 3) = -true_up.dot(eye);
  view(2, 3) = forward.dot(eye);
  return view.cast<float>();
}

Eigen::Matrix4f Camera::projection_matrix(double aspect) const {
  if (!(aspect > 0.0) || !std::isfinite(aspect)) {
    throw std::invalid_argument("Camera: aspect ratio must be positive, got " +
                                std::to_string(aspect));
  }
  if (!(fov_y_deg > 0.0 && fov_y_deg < 180.0)) {
    throw std::invalid_argument("Camera: fov_y_deg must be in (0, 180), got " +
                                std::to_string(fov_y_deg));
  }
  if (!(near_m > 0.0 && far_m > near_m) || !std::isfinite(far_m)) {
    throw std::invalid_argument("Camera: need 0 < near_m < far_m, got near_m = " +
                                std::to_string(near_m) + ", far_m = " + std::to_string(far_m));
  }
  const double focal = 1.0 / std::tan(0.5 * fov_y_deg * base::kPi / 180.0);
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = focal / aspect;
  projection(1, 1) = focal;
  projection(2, 2) = (far_m + near_m) / (near_m - far_m);
  projection(2, 3) = 2.0 * far_m * near_m / (near_m - far_m);
  projection(3, 2) = -1.0;
  return projection.cast<float>();
}

}  // namespace weft::render
