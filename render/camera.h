#pragma once
// The camera shared by the renderers: a pinhole look-at camera (eye, target, up, vertical field
// of view), or a calibrated pinhole in OpenCV's convention (docs/photos.md,
// "Calibrated cameras"):
//
// - camera frame: x right, y down, z forward (into the scene), metres;
// - pixel (u, v): u along the columns (to the right), v along the rows (down), the CENTRE of
//   the top-left pixel at (0, 0), so pixel (i, j) covers [i − ½, i + ½] × [j − ½, j + ½] and
//   the image spans u ∈ [−½, width − ½];
// - a camera-frame point (X, Y, Z), Z > 0, projects to u = fx X / Z + cx, v = fy Y / Z + cy;
// - the pose is camera → world: a world point p = R (X, Y, Z) + t, R's columns the camera's x,
//   y and z axes in world coordinates (weft's world: z up, metres), t the camera's position.
//
// Both renderers draw through projection_matrix(width, height) and view_matrix(), so they
// agree; project() gives the same pixel (u, v) in double precision for any camera.

#include <Eigen/Core>
#include <optional>

namespace weft::render {

// Intrinsics of a calibrated pinhole, in pixels of a width_px × height_px image (conventions
// above). cx, cy need not lie inside the image.
struct PinholeIntrinsics {
  double fx_px = 0.0, fy_px = 0.0;  // focal lengths, > 0
  double cx_px = 0.0, cy_px = 0.0;  // principal point
  int width_px = 0, height_px = 0;  // the image size the intrinsics are given for

  // The intrinsics for an image of width × height with the same aspect ratio (within 1 %),
  // e.g. a downscaled render: each axis scaled by its own factor s = new / old size, with
  // f' = s f and c' = s (c + ½) − ½ (the image edges stay the edges). Throws
  // std::invalid_argument when the aspect ratios differ, naming both sizes.
  PinholeIntrinsics scaled_to(int width, int height) const;
};

// Throws std::invalid_argument ("PinholeIntrinsics: fx_px must be finite and > 0, got -3")
// unless the focal lengths are finite and positive, the principal point finite and the image
// size positive.
void validate(const PinholeIntrinsics& k);

// A camera-to-world rotation (columns: the camera's x right, y down, z forward in world
// coordinates), checked orthonormal within `tolerance` (max |RᵀR − I|) and proper (det +1),
// then re-orthonormalised (nearest rotation, by SVD) so that round-off in a calibration file
// does not shear the view. Throws std::invalid_argument saying which check failed and by how
// much.
Eigen::Matrix3d checked_rotation(const Eigen::Matrix3d& camera_to_world, double tolerance = 1e-4);

struct Camera {
  Eigen::Vector3d eye{2.0, -2.5, 1.2};     // metres
  Eigen::Vector3d target{0.0, 0.0, 0.5};  // metres
  Eigen::Vector3d up{0.0, 0.0, 1.0};
  double fov_y_deg = 40.0;                 // vertical field of view
  double near_m = 0.01, far_m = 100.0;     // depth range along the view axis

  // Set (by calibrated()) for a calibrated pinhole: then these intrinsics and `rotation`
  // define the view; eye is the camera's position, target eye + z axis (1 m ahead), up the
  // camera's −y axis and fov_y_deg the vertical field of view at the principal point, kept
  // for the code that reads them (the ground square is centred under the target).
  std::optional<PinholeIntrinsics> intrinsics;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // camera → world (calibrated only)

  // A calibrated pinhole at `position_m` with camera-to-world rotation `rotation` (columns x
  // right, y down, z forward); checks both (validate, checked_rotation) and throws
  // std::invalid_argument.
  static Camera calibrated(const PinholeIntrinsics& intrinsics, const Eigen::Matrix3d& rotation,
                           const Eigen::Vector3d& position_m);
  // The same from a 4×4 camera-to-world matrix [R t; 0 0 0 1].
  static Camera calibrated(const PinholeIntrinsics& intrinsics,
                           const Eigen::Matrix4d& camera_to_world);

  // World → OpenGL camera frame (x right, y up, looking down −z).
  Eigen::Matrix4d view_matrix_d() const;
  Eigen::Matrix4f view_matrix() const { return view_matrix_d().cast<float>(); }
  // Camera → clip for an image of width × height pixels (OpenGL: near → NDC z = −1, far → +1).
  // Look-at: projection_matrix(width / height); calibrated: the intrinsics scaled to the
  // image (PinholeIntrinsics::scaled_to), principal point included.
  Eigen::Matrix4d projection_matrix_d(int width, int height) const;
  Eigen::Matrix4f projection_matrix(int width, int height) const {
    return projection_matrix_d(width, height).cast<float>();
  }
  // Look-at cameras only: the symmetric frustum of fov_y_deg and aspect = width / height.
  Eigen::Matrix4f projection_matrix(double aspect) const;

  // The pixel (u, v) (conventions above) where world point `world_m` appears in a width ×
  // height image of this camera, and its depth along the view axis in metres (z; ≤ 0 behind
  // the camera, where u, v mean nothing).
  Eigen::Vector3d project(const Eigen::Vector3d& world_m, int width, int height) const;

 private:
  Eigen::Matrix4d look_at_projection(double aspect) const;
};

}  // namespace weft::render
