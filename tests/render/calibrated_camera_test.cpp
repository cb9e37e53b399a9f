// Calibrated pinhole cameras (render/camera.h), checked against OpenCV's projection written
// out independently here: X = Rᵀ (p − t), u = fx X/Z + cx, v = fy Y/Z + cy, the centre of the
// top-left pixel at (0, 0); downscaled images keep the image edges (u + ½ scales).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/camera.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

PinholeIntrinsics off_centre_intrinsics() {
  PinholeIntrinsics k;
  k.fx_px = 520.0;  // fx ≠ fy: non-square pixels
  k.fy_px = 585.0;
  k.cx_px = 351.3;  // off the centre (319.5, 239.5) in both directions
  k.cy_px = 221.7;
  k.width_px = 640;
  k.height_px = 480;
  return k;
}

Eigen::Vector2d opencv_pixel(const PinholeIntrinsics& k, const Eigen::Matrix3d& r,
                             const Eigen::Vector3d& t, const Eigen::Vector3d& p) {
  const Eigen::Vector3d c = r.transpose() * (p - t);
  return {k.fx_px * c.x() / c.z() + k.cx_px, k.fy_px * c.y() / c.z() + k.cy_px};
}

TEST(CalibratedCamera, ProjectsAsOpenCVAtTheCalibratedSize) {
  const PinholeIntrinsics k = off_centre_intrinsics();
  const Eigen::Vector3d eye(0.4, -1.7, 0.9);
  const Eigen::Matrix3d r = test::opencv_look_at(eye, {0.0, 0.0, 0.3}, 0.2);
  const Camera camera = Camera::calibrated(k, r, eye);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0.25, 0.1, 0.0),
                                   Eigen::Vector3d(-0.3, 0.2, 0.6), Eigen::Vector3d(0.1, -0.4, 1.0)}) {
    const Eigen::Vector3d got = camera.project(p, 640, 480);
    const Eigen::Vector2d want = opencv_pixel(k, r, eye, p);
    EXPECT_NEAR(got.x(), want.x(), 1e-9) << p.transpose();
    EXPECT_NEAR(got.y(), want.y(), 1e-9) << p.transpose();
    EXPECT_NEAR(got.z(), (r.transpose() * (p - eye)).z(), 1e-12) << "depth along the view axis";
  }
  // The principal point is where the optical axis lands.
  const Eigen::Vector3d axis_point = camera.project(eye + 2.0 * r.col(2), 640, 480);
  EXPECT_NEAR(axis_point.x(), k.cx_px, 1e-9);
  EXPECT_NEAR(axis_point.y(), k.cy_px, 1e-9);
}

TEST(CalibratedCamera, DownscaledImageKeepsTheImageEdges) {
  const PinholeIntrinsics k = off_centre_intrinsics();
  const PinholeIntrinsics half = k.scaled_to(320, 240);
  EXPECT_DOUBLE_EQ(half.fx_px, 260.0);
  EXPECT_DOUBLE_EQ(half.fy_px, 292.5);
  EXPECT_DOUBLE_EQ(half.cx_px, 0.5 * (351.3 + 0.5) - 0.5);
  EXPECT_DOUBLE_EQ(half.cy_px, 0.5 * (221.7 + 0.5) - 0.5);
  const Eigen::Vector3d eye(0.4, -1.7, 0.9);
  const Eigen::Matrix3d r = test::opencv_look_at(eye, {0.0, 0.0, 0.3}, -0.3);
  const Camera camera = Camera::calibrated(k, r, eye);
  const Eigen::Vector3d p(0.2, -0.1, 0.45);
  const Eigen::Vector2d full = opencv_pixel(k, r, eye, p);
  const Eigen::Vector3d small = camera.project(p, 320, 240);
  EXPECT_NEAR(small.x(), 0.5 * (full.x() + 0.5) - 0.5, 1e-9);
  EXPECT_NEAR(small.y(), 0.5 * (full.y() + 0.5) - 0.5, 1e-9);
  // A different aspect ratio is refused, naming both sizes.
  try {
    (void)camera.project(p, 320, 320);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("320x320"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos) << e.what();
  }
}

TEST(CalibratedCamera, MatrixPoseEqualsPositionAndRotation) {
  const PinholeIntrinsics k = off_centre_intrinsics();
  const Eigen::Vector3d eye(-1.2, 0.5, 1.4);
  const Eigen::Matrix3d r = test::opencv_look_at(eye, {0.1, 0.0, 0.2}, 0.7);
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose.topLeftCorner<3, 3>() = r;
  pose.topRightCorner<3, 1>() = eye;
  const Camera a = Camera::calibrated(k, r, eye), b = Camera::calibrated(k, pose);
  EXPECT_TRUE(a.view_matrix_d().isApprox(b.view_matrix_d(), 1e-14));
  // Look-at fields kept for the code that reads them: eye, 1 m ahead, −y up.
  EXPECT_TRUE(a.eye.isApprox(eye));
  EXPECT_NEAR((a.target - (eye + r.col(2))).norm(), 0.0, 1e-12);
  EXPECT_NEAR((a.up + r.col(1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(a.fov_y_deg, 2.0 * std::atan(240.0 / 585.0) * 180.0 / 3.14159265358979323846, 1e-9);
}

TEST(CalibratedCamera, LookAtCameraPutsItsTargetAtTheImageCentre) {
  Camera camera;  // the default look-at camera: the target lands at the image centre
  const Eigen::Vector3d centre = camera.project(camera.target, 640, 480);
  EXPECT_NEAR(centre.x(), 319.5, 1e-4);
  EXPECT_NEAR(centre.y(), 239.5, 1e-4);
  EXPECT_NEAR(centre.z(), (camera.target - camera.eye).norm(), 1e-12);
}

TEST(CalibratedCamera, BadInputThrowsSayingWhat) {
  const auto message = [](const auto& f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(no exception)";
  };
  const Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d t = Eigen::Vector3d::Zero();
  PinholeIntrinsics k = off_centre_intrinsics();
  k.fx_px = -3.0;
  EXPECT_NE(message([&] { Camera::calibrated(k, r, t); }).find("fx_px must be finite and > 0"),
            std::string::npos);
  k = off_centre_intrinsics();
  k.width_px = 0;
  EXPECT_NE(message([&] { Camera::calibrated(k, r, t); }).find("image size"), std::string::npos);
  k = off_centre_intrinsics();
  Eigen::Matrix3d sheared = r;
  sheared(0, 1) = 0.01;
  EXPECT_NE(message([&] { Camera::calibrated(k, sheared, t); }).find("not orthonormal"),
            std::string::npos);
  Eigen::Matrix3d mirrored = r;
  mirrored(1, 1) = -1.0;  // y up instead of down: a reflection
  EXPECT_NE(message([&] { Camera::calibrated(k, mirrored, t); }).find("reflection"),
            std::string::npos);
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose(3, 0) = 0.5;
  EXPECT_NE(message([&] { Camera::calibrated(k, pose); }).find("last row"), std::string::npos);
  // Round-off within the tolerance is accepted and removed: the rotation comes out orthonormal.
  Eigen::Matrix3d rounded = test::opencv_look_at({1, -2, 1}, {0, 0, 0}, 0.1);
  rounded(0, 0) += 2e-5;
  const Camera c = Camera::calibrated(k, rounded, {1, -2, 1});
  EXPECT_LT((c.rotation.transpose() * c.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  // A calibrated camera has no projection from an aspect ratio alone.
  EXPECT_NE(message([&] { (void)c.projection_matrix(4.0 / 3.0); }).find("image size"),
            std::string::npos);
}

}  // namespace
}  // namespace weft::render
