// Look-at and calibrated pinhole cameras (see camera.h). OpenGL conventions for the matrices:
// the camera looks down its −z axis with +y up; clip space maps near → NDC z = −1 and
// far → +1; NDC x = −1 is the left image edge and y = +1 the top edge.

#include "render/camera.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace weft::render {

namespace {

std::string text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

void check_depth_range(double near_m, double far_m) {
  if (!(near_m > 0.0 && far_m > near_m) || !std::isfinite(far_m)) {
    throw std::invalid_argument("Camera: need 0 < near_m < far_m, got near_m = " +
                                std::to_string(near_m) + ", far_m = " + std::to_string(far_m));
  }
}

// Rows 2 and 3 of an OpenGL perspective projection: depth near → −1, far → +1, w = −z.
void set_depth_rows(double near_m, double far_m, Eigen::Matrix4d& projection) {
  projection(2, 2) = (far_m + near_m) / (near_m - far_m);
  projection(2, 3) = 2.0 * far_m * near_m / (near_m - far_m);
  projection(3, 2) = -1.0;
}

}  // namespace

void validate(const PinholeIntrinsics& k) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("PinholeIntrinsics: " + what);
  };
  if (!(k.fx_px > 0.0) || !std::isfinite(k.fx_px))
    fail("fx_px must be finite and > 0, got " + text(k.fx_px));
  if (!(k.fy_px > 0.0) || !std::isfinite(k.fy_px))
    fail("fy_px must be finite and > 0, got " + text(k.fy_px));
  if (!std::isfinite(k.cx_px) || !std::isfinite(k.cy_px))
    fail("the principal point must be finite, got (" + text(k.cx_px) + ", " + text(k.cy_px) + ")");
  if (k.width_px <= 0 || k.height_px <= 0)
    fail("the image size must be positive, got " + size_text(k.width_px, k.height_px));
}

PinholeIntrinsics PinholeIntrinsics::scaled_to(int width, int height) const {
  validate(*this);
  if (width == width_px && height == height_px) return *this;
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("PinholeIntrinsics: image size must be positive, got " +
                                size_text(width, height));
  const double sx = static_cast<double>(width) / width_px;
  const double sy = static_cast<double>(height) / height_px;
  if (std::abs(sx / sy - 1.0) > 0.01) {
    throw std::invalid_argument(
        "PinholeIntrinsics: the image is " + size_text(width, height) + " but the intrinsics are " +
        "for " + size_text(width_px, height_px) + ", a different aspect ratio (scales " + text(sx) +
        " and " + text(sy) + " differ by more than 1 %)");
  }
  PinholeIntrinsics k = *this;
  k.fx_px = sx * fx_px;
  k.fy_px = sy * fy_px;
  k.cx_px = sx * (cx_px + 0.5) - 0.5;
  k.cy_px = sy * (cy_px + 0.5) - 0.5;
  k.width_px = width;
  k.height_px = height;
  return k;
}

Eigen::Matrix3d checked_rotation(const Eigen::Matrix3d& r, double tolerance) {
  if (!r.allFinite()) throw std::invalid_argument("Camera: the rotation has a non-finite entry");
  const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(error <= tolerance)) {
    throw std::invalid_argument("Camera: the rotation is not orthonormal: max |R^T R - I| = " +
                                text(error) + " (tolerance " + text(tolerance) + ")");
  }
  if (!(r.determinant() > 0.0)) {
    throw std::invalid_argument(
        "Camera: the rotation has determinant " + text(r.determinant()) +
        ", a reflection (expected +1: columns x right, y down, z forward, right-handed)");
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

Camera Camera::calibrated(const PinholeIntrinsics& intrinsics, const Eigen::Matrix3d& rotation,
                          const Eigen::Vector3d& position_m) {
  validate(intrinsics);
  if (!position_m.allFinite())
    throw std::invalid_argument("Camera: the position has a non-finite coordinate");
  Camera c;
  c.intrinsics = intrinsics;
  c.rotation = checked_rotation(rotation);
  c.eye = position_m;
  c.target = position_m + c.rotation.col(2);
  c.up = -c.rotation.col(1);
  c.fov_y_deg = 2.0 * std::atan(0.5 * intrinsics.height_px / intrinsics.fy_px) * 180.0 / base::kPi;
  return c;
}

Camera Camera::calibrated(const PinholeIntrinsics& intrinsics,
                          const Eigen::Matrix4d& camera_to_world) {
  const Eigen::RowVector4d last = camera_to_world.row(3);
  if (!((last - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() <= 1e-12)) {
    throw std::invalid_argument("Camera: the camera-to-world matrix's last row must be [0, 0, 0, 1]");
  }
  return calibrated(intrinsics, camera_to_world.topLeftCorner<3, 3>(),
                    camera_to_world.topRightCorner<3, 1>());
}

Eigen::Matrix4d Camera::view_matrix_d() const {
  Eigen::Matrix3d rows;  // the OpenGL camera axes x, y, z as rows, in world coordinates
  if (intrinsics) {
    rows.row(0) = rotation.col(0).transpose();
    rows.row(1) = -rotation.col(1).transpose();
    rows.row(2) = -rotation.col(2).transpose();
  } else {
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
    rows.row(0) = side.transpose();
    rows.row(1) = side.cross(forward).transpose();  // camera +y
    rows.row(2) = -forward.transpose();
  }
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.topLeftCorner<3, 3>() = rows;
  view(0, 3) = -rows.row(0).dot(eye);
  view(1, 3) = -rows.row(1).dot(eye);
  view(2, 3) = -rows.row(2).dot(eye);
  return view;
}

Eigen::Matrix4f Camera::projection_matrix(double aspect) const {
  if (intrinsics) {
    throw std::invalid_argument(
        "Camera: a calibrated camera's projection needs the image size, not only its aspect");
  }
  return look_at_projection(aspect).cast<float>();
}

Eigen::Matrix4d Camera::look_at_projection(double aspect) const {
  if (!(aspect > 0.0) || !std::isfinite(aspect)) {
    throw std::invalid_argument("Camera: aspect ratio must be positive, got " +
                                std::to_string(aspect));
  }
  if (!(fov_y_deg > 0.0 && fov_y_deg < 180.0)) {
    throw std::invalid_argument("Camera: fov_y_deg must be in (0, 180), got " +
                                std::to_string(fov_y_deg));
  }
  check_depth_range(near_m, far_m);
  const double focal = 1.0 / std::tan(0.5 * fov_y_deg * base::kPi / 180.0);
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = focal / aspect;
  projection(1, 1) = focal;
  set_depth_rows(near_m, far_m, projection);
  return projection;
}

// Calibrated: NDC x = 2 (u + ½) / width − 1 and NDC y = 1 − 2 (v + ½) / height, with
// u = fx X/Z + cx, v = fy Y/Z + cy and (X, Y, Z) = (x, −y, −z) of the OpenGL camera frame.
Eigen::Matrix4d Camera::projection_matrix_d(int width, int height) const {
  if (!intrinsics) {
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    return look_at_projection(aspect);
  }
  check_depth_range(near_m, far_m);
  const PinholeIntrinsics k = intrinsics->scaled_to(width, height);
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = 2.0 * k.fx_px / width;
  projection(0, 2) = 1.0 - 2.0 * (k.cx_px + 0.5) / width;
  projection(1, 1) = 2.0 * k.fy_px / height;
  projection(1, 2) = 2.0 * (k.cy_px + 0.5) / height - 1.0;
  set_depth_rows(near_m, far_m, projection);
  return projection;
}

Eigen::Vector3d Camera::project(const Eigen::Vector3d& world_m, int width, int height) const {
  const Eigen::Vector4d eye_space = view_matrix_d() * world_m.homogeneous();
  const Eigen::Vector4d clip = projection_matrix_d(width, height) * eye_space;
  const double depth = -eye_space.z();
  const double x_ndc = clip.x() / clip.w(), y_ndc = clip.y() / clip.w();
  return {0.5 * (x_ndc + 1.0) * width - 0.5, 0.5 * (1.0 - y_ndc) * height - 0.5, depth};
}

}  // namespace weft::render
