// Look-at camera: OpenGL view and projection conventions.

#include "render/camera.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>

namespace weft::render {
namespace {

Eigen::Vector4f to_clip(const Camera& camera, double aspect, const Eigen::Vector3d& world) {
  return camera.projection_matrix(aspect) * camera.view_matrix() *
         Eigen::Vector4f(world.cast<float>().homogeneous());
}

Eigen::Vector3f to_ndc(const Camera& camera, double aspect, const Eigen::Vector3d& world) {
  const Eigen::Vector4f clip = to_clip(camera, aspect, world);
  return clip.head<3>() / clip.w();
}

TEST(Camera, TargetProjectsToTheCentre) {
  const Camera camera;  // default: oblique view from (2, −2.5, 1.2)
  const Eigen::Vector3f ndc = to_ndc(camera, 4.0 / 3.0, camera.target);
  EXPECT_NEAR(ndc.x(), 0.0f, 1e-6f);
  EXPECT_NEAR(ndc.y(), 0.0f, 1e-6f);
  EXPECT_GT(ndc.z(), -1.0f);
  EXPECT_LT(ndc.z(), 1.0f);
}

TEST(Camera, PointAboveTheTargetIsUpOnScreen) {
  const Camera camera;
  const Eigen::Vector3f ndc = to_ndc(camera, 1.0, camera.target + 0.1 * camera.up);
  EXPECT_NEAR(ndc.x(), 0.0f, 1e-6f);
  EXPECT_GT(ndc.y(), 0.0f);
}

TEST(Camera, TargetIsInFrontOfTheEye) {
  Camera camera;
  camera.eye = {1, 2, 3};
  camera.target = {-2, 0.5, 0.25};
  const Eigen::Vector4f eye_space =
      camera.view_matrix() * Eigen::Vector4f(camera.target.cast<float>().homogeneous());
  EXPECT_NEAR(eye_space.z(), -static_cast<float>((camera.target - camera.eye).norm()), 1e-5f);
  // The eye itself is the eye-space origin.
  const Eigen::Vector4f eye_origin =
      camera.view_matrix() * Eigen::Vector4f(camera.eye.cast<float>().homogeneous());
  EXPECT_LT(eye_origin.head<3>().norm(), 1e-5f);
}

TEST(Camera, RightHandedScreen) {
  // Right = forward × up. From −y looking along +y with z up, +x is on the right; from +y
  // looking along −y, −x is.
  Camera camera;
  camera.target = {0, 0, 0};
  camera.up = {0, 0, 1};
  camera.eye = {0, -5, 0};
  EXPECT_GT(to_ndc(camera, 1.0, {0.5, 0, 0}).x(), 0.0f);
  camera.eye = {0, 5, 0};
  EXPECT_LT(to_ndc(camera, 1.0, {0.5, 0, 0}).x(), 0.0f);
}

TEST(Camera, NearAndFarPlanesMapToMinusOneAndOne) {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.up = {0, 1, 0};
  camera.near_m = 0.5;
  camera.far_m = 20.0;
  EXPECT_NEAR(to_ndc(camera, 1.0, {0, 0, -0.5}).z(), -1.0f, 1e-5f);
  EXPECT_NEAR(to_ndc(camera, 1.0, {0, 0, -20.0}).z(), 1.0f, 1e-4f);
}

TEST(Camera, FieldOfViewSpansTheScreenHeight) {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.up = {0, 1, 0};
  camera.fov_y_deg = 90.0;  // tan(45°) = 1: at depth 2 the half-height is 2
  EXPECT_NEAR(to_ndc(camera, 2.0, {0, 2, -2}).y(), 1.0f, 1e-6f);
  EXPECT_NEAR(to_ndc(camera, 2.0, {4, 0, -2}).x(), 1.0f, 1e-6f);  // aspect 2: twice as wide
}

TEST(Camera, DegenerateSetupsThrow) {
  Camera camera;
  camera.up = (camera.target - camera.eye);
  EXPECT_THROW(camera.view_matrix(), std::invalid_argument);
  camera = Camera{};
  camera.eye = camera.target;
  EXPECT_THROW(camera.view_matrix(), std::invalid_argument);
  camera = Camera{};
  EXPECT_THROW(camera.projection_matrix(0.0), std::invalid_argument);
  camera.near_m = 0.0;
  EXPECT_THROW(camera.projection_matrix(1.0), std::invalid_argument);
}

}  // namespace
}  // namespace weft::render
