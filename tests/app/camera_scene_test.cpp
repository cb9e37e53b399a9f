// render.camera as a calibrated pinhole and output.mask / output.alpha: the three ways to give the
// pose describe one camera, and each mistake gets a message naming the key path and what was
// expected.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

using render::Camera;

// A scene with a calibrated camera `camera` (a JSON object) and a 320×240 render.
Json scene_with_camera(const Json& camera) {
  Json scene = Json::parse(R"({
    "description": "calibrated camera test scene",
    "cloth": {"size": ["1 m", "1 m"], "resolution": [9, 9]},
    "output": {"frames": 2},
    "render": {"size": [320, 240]}
  })");
  scene["render"]["camera"] = camera;
  return scene;
}

Json intrinsics() {
  return Json::parse(R"({"fx": 520, "fy": 585, "cx": 351.3, "cy": 221.7, "size": [640, 480]})");
}

// Looking from (0.4, −1.7, 0.9) towards the origin: camera x, y (down), z as matrix columns.
Eigen::Matrix3d pose_rotation() {
  const Eigen::Vector3d eye(0.4, -1.7, 0.9);
  const Eigen::Vector3d z = (-eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Matrix3d r;
  r << x, z.cross(x), z;
  return r;
}

Json rows(const Eigen::MatrixXd& m) {
  Json out = Json::array();
  for (int i = 0; i < m.rows(); ++i) {
    Json row = Json::array();
    for (int j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    out.push_back(row);
  }
  return out;
}

TEST(CameraScene, ThreePoseFormsGiveOneCamera) {
  const Eigen::Matrix3d r = pose_rotation();
  const Eigen::Vector3d t(0.4, -1.7, 0.9);
  Eigen::Matrix4d camera_to_world = Eigen::Matrix4d::Identity();
  camera_to_world.topLeftCorner<3, 3>() = r;
  camera_to_world.topRightCorner<3, 1>() = t;
  const Eigen::Matrix4d world_to_camera = camera_to_world.inverse();

  const Scene a = test::parse_json_scene(scene_with_camera(
      {{"intrinsics", intrinsics()}, {"position", {0.4, -1.7, 0.9}}, {"rotation", rows(r)}}));
  const Scene b = test::parse_json_scene(
      scene_with_camera({{"intrinsics", intrinsics()}, {"camera_to_world", rows(camera_to_world)}}));
  const Scene c = test::parse_json_scene(scene_with_camera(
      {{"intrinsics", intrinsics()}, {"world_to_camera", rows(world_to_camera)}, {"far", "20 m"}}));
  ASSERT_TRUE(a.render.camera.intrinsics.has_value());
  EXPECT_DOUBLE_EQ(a.render.camera.intrinsics->fy_px, 585.0);
  EXPECT_EQ(a.render.camera.intrinsics->width_px, 640);
  for (const Scene* s : {&b, &c}) {
    EXPECT_TRUE(s->render.camera.view_matrix_d().isApprox(a.render.camera.view_matrix_d(), 1e-12));
    const Eigen::Matrix4d pa = a.render.camera.projection_matrix_d(320, 240);
    const Eigen::Matrix4d ps = s->render.camera.projection_matrix_d(320, 240);
    EXPECT_TRUE(ps.row(0).isApprox(pa.row(0)) && ps.row(1).isApprox(pa.row(1)));
  }
  EXPECT_DOUBLE_EQ(c.render.camera.far_m, 20.0);
  // The origin lands where OpenCV puts it in the half-size image.
  const Eigen::Vector3d cam = r.transpose() * (-t);
  const double u = 0.5 * (520.0 * cam.x() / cam.z() + 351.3 + 0.5) - 0.5;
  const double v = 0.5 * (585.0 * cam.y() / cam.z() + 221.7 + 0.5) - 0.5;
  const Eigen::Vector3d got = a.render.camera.project(Eigen::Vector3d::Zero(), 320, 240);
  EXPECT_NEAR(got.x(), u, 1e-9);
  EXPECT_NEAR(got.y(), v, 1e-9);
}

// docs/photos.md's worked example: the φ-SfT R1 intrinsics at quarter size.
TEST(CameraScene, WorkedExampleOfTheDocs) {
  Json scene = scene_with_camera(Json::parse(R"({
    "intrinsics": {"fx": 971.522, "fy": 944.575, "cx": 962.134, "cy": 554.778,
                   "size": [1920, 1080]},
    "position": [0, -1.2, 0.4],
    "rotation": [[1, 0, 0], [0, 0, 1], [0, -1, 0]]})"));
  scene["render"]["size"] = {480, 270};
  const Camera& camera = test::parse_json_scene(scene).render.camera;
  const Eigen::Vector3d full = camera.project({0.1, 0.0, 0.3}, 1920, 1080);
  EXPECT_NEAR(full.x(), 1043.094, 1e-3);
  EXPECT_NEAR(full.y(), 633.493, 1e-3);
  EXPECT_NEAR(full.z(), 1.2, 1e-12);
  const Eigen::Vector3d quarter = camera.project({0.1, 0.0, 0.3}, 480, 270);
  EXPECT_NEAR(quarter.x(), 260.399, 1e-3);
  EXPECT_NEAR(quarter.y(), 157.998, 1e-3);
}

TEST(CameraScene, MistakesAreNamed) {
  const Eigen::Matrix3d r = pose_rotation();
  const auto error = [](const Json& camera) { return test::scene_error_of(scene_with_camera(camera)); };
  Json k = intrinsics();
  k["fx"] = 0;
  EXPECT_CONTAINS(error({{"intrinsics", k}, {"position", {0, 0, 1}}, {"rotation", rows(r)}}),
                  "render.camera.intrinsics.fx: expected a number > 0, got 0");
  k = intrinsics();
  k.erase("cy");
  EXPECT_CONTAINS(error({{"intrinsics", k}, {"position", {0, 0, 1}}, {"rotation", rows(r)}}),
                  "render.camera.intrinsics.cy");
  Eigen::Matrix3d sheared = r;
  sheared(0, 1) += 0.01;
  EXPECT_CONTAINS(error({{"intrinsics", intrinsics()}, {"position", {0, 0, 1}},
                         {"rotation", rows(sheared)}}),
                  "render.camera.rotation: Camera: the rotation is not orthonormal");
  Eigen::Matrix3d mirrored = r;
  mirrored.col(1) *= -1.0;  // y up: a reflection
  EXPECT_CONTAINS(error({{"intrinsics", intrinsics()}, {"position", {0, 0, 1}},
                         {"rotation", rows(mirrored)}}),
                  "reflection");
  EXPECT_CONTAINS(error({{"intrinsics", intrinsics()}, {"position", {0, 0, 1}},
                         {"rotation", {{1, 0, 0}, {0, 1, 0}}}}),
                  "render.camera.rotation: expected an array of 3 rows");
  EXPECT_CONTAINS(error({{"intrinsics", intrinsics()}, {"position", {0, 0, 1}}}),
                  "expected exactly one pose");
  EXPECT_CONTAINS(error({{"intrinsics", intrinsics()}, {"position", {0, 0, 1}},
                         {"rotation", rows(r)}, {"camera_to_world", rows(Eigen::Matrix4d::Identity())}}),
                  "expected exactly one pose");
  EXPECT_CONTAINS(error({{"intrinsics", intrinsics()}, {"eye", {0, 0, 1}}, {"position", {0, 0, 1}},
                         {"rotation", rows(r)}}),
                  "render.camera.eye: a calibrated camera");
  k = intrinsics();
  k["size"] = {640, 640};  // the render is 320×240
  EXPECT_CONTAINS(error({{"intrinsics", k}, {"position", {0, 0, 1}}, {"rotation", rows(r)}}),
                  "render.size: PinholeIntrinsics: the image is 320x240 but the intrinsics are for "
                  "640x640");
}

TEST(CameraScene, MaskAndAlphaOutputs) {
  Json scene = scene_with_camera(Json::parse(R"({"eye": [1, -2, 1]})"));
  EXPECT_FALSE(test::parse_json_scene(scene).write_mask);
  scene["output"]["mask"] = true;
  scene["output"]["alpha"] = true;
  const Scene s = test::parse_json_scene(scene);
  EXPECT_TRUE(s.write_mask);
  EXPECT_TRUE(s.write_alpha);
  scene["output"]["mask"] = "yes";
  EXPECT_CONTAINS(test::scene_error_of(scene), "output.mask");
}

}  // namespace
}  // namespace weft::app
