// Obstacles in scene files: "obstacles" (spheres, planes, boxes, cylinders, capsules),
// "simulation.collision_thickness" and "render.colors.obstacle" land in SI units; every mistake
// names its key path. And the render objects made from them (app/run/obstacle_meshes.h).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/scene/json_reader.h"
#include "app/run/obstacle_meshes.h"
#include "app/scene/scene.h"
#include "base/constants.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

using test::parse_json_scene;
using test::scene_error_of;

// A valid scene with a sphere above the ground plane, to be broken one key at a time.
Json scene_with_obstacles() {
  return Json::parse(R"({
    "description": "test scene with obstacles",
    "cloth": {"size": ["1 m", "1 m"], "resolution": [11, 11], "origin": [-0.5, -0.5, 0.9]},
    "obstacles": [
      {"sphere": {"center": ["0 m", "10 cm", "0.5 m"], "radius": "15 cm"}},
      {"plane": {"point": [0, 0, "-2 cm"], "normal": [0, 0, 1]}}
    ],
    "simulation": {"collision_thickness": "1 mm"},
    "render": {"colors": {"obstacle": [0.5, 0.6, 0.7]}}
  })");
}

TEST(ObstacleScene, SpheresAndPlanesLandInSIUnits) {
  const Scene s = parse_json_scene(scene_with_obstacles());
  ASSERT_EQ(s.sim.obstacles.size(), 2u);
  const auto& sphere = std::get<sim::SphereObstacle>(s.sim.obstacles[0]);
  EXPECT_EQ(sphere.center_m, Eigen::Vector3d(0.0, 0.1, 0.5));
  EXPECT_NEAR(sphere.radius_m, 0.15, 1e-15);
  const auto& plane = std::get<sim::PlaneObstacle>(s.sim.obstacles[1]);
  EXPECT_NEAR(plane.point_m.z(), -0.02, 1e-15);
  EXPECT_EQ(plane.normal, Eigen::Vector3d(0, 0, 1));
  EXPECT_NEAR(s.sim.collision_thickness_m, 0.001, 1e-15);
  EXPECT_EQ(s.render.obstacle_color, Eigen::Vector3f(0.5f, 0.6f, 0.7f));
}

TEST(ObstacleScene, DefaultsAreNoObstaclesAndTwoMillimetres) {
  Json j = scene_with_obstacles();
  j.erase("obstacles");
  j.erase("simulation");
  j.erase("render");
  const Scene s = parse_json_scene(j);
  EXPECT_TRUE(s.sim.obstacles.empty());
  EXPECT_EQ(s.sim.collision_thickness_m, 2e-3);
  EXPECT_EQ(s.render.obstacle_color, render::RenderSettings{}.obstacle_color);
  j["obstacles"] = Json::array();
  EXPECT_TRUE(parse_json_scene(j).sim.obstacles.empty());
}

TEST(ObstacleScene, NearlyUnitNormalIsNormalised) {
  Json j = scene_with_obstacles();
  j["obstacles"][1]["plane"]["normal"] = {0, 0.6, 0.8000004};
  const Scene scene = parse_json_scene(j);
  const auto& plane = std::get<sim::PlaneObstacle>(scene.sim.obstacles[1]);
  EXPECT_NEAR(plane.normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR(plane.normal.y(), 0.6, 1e-6);
}

TEST(ObstacleScene, EachObstacleIsExactlyOneShape) {
  Json j = scene_with_obstacles();
  j["obstacles"][0] = Json::object();
  EXPECT_EQ(scene_error_of(j),
            "scene.json: obstacles[0]: expected exactly one of 'sphere', 'plane', 'box', "
            "'cylinder', 'capsule' or 'mesh', got none");
  j = scene_with_obstacles();
  j["obstacles"][1]["sphere"] = j["obstacles"][0]["sphere"];
  EXPECT_EQ(scene_error_of(j),
            "scene.json: obstacles[1]: expected exactly one of 'sphere', 'plane', 'box', "
            "'cylinder', 'capsule' or 'mesh', got 'sphere' and 'plane'");
  j = scene_with_obstacles();
  j["obstacles"][0]["capsule"] = j["obstacles"][0]["sphere"];
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0]: expected exactly one of");
  j = scene_with_obstacles();
  j["obstacles"][0]["spehre"] = j["obstacles"][0]["sphere"];
  j["obstacles"][0].erase("sphere");
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: obstacles[0].spehre: unknown key; did you mean 'sphere'?");
  j = scene_with_obstacles();
  j["obstacles"][0]["color"] = "red";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].color: unknown key");
}

TEST(ObstacleScene, WrongTypes) {
  Json j = scene_with_obstacles();
  j["obstacles"] = j["obstacles"][0];
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles: expected an array of objects");
  j = scene_with_obstacles();
  j["obstacles"][1] = 5;
  EXPECT_EQ(scene_error_of(j), "scene.json: obstacles[1]: expected an object, got 5");
  j = scene_with_obstacles();
  j["obstacles"][0]["sphere"] = 0.15;
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere: expected an object");
}

TEST(ObstacleScene, BadSphere) {
  Json j = scene_with_obstacles();
  j["obstacles"][0]["sphere"]["radius"] = 0;
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere.radius: expected a length > 0");
  j["obstacles"][0]["sphere"]["radius"] = "-15 cm";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere.radius: expected a length > 0");
  j["obstacles"][0]["sphere"]["radius"] = "15 kg";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere.radius: expected a length");
  j["obstacles"][0]["sphere"].erase("radius");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere.radius: required key is missing");
  j = scene_with_obstacles();
  j["obstacles"][0]["sphere"]["center"] = {0, 0};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere.center: expected an array of 3");
  j["obstacles"][0]["sphere"].erase("center");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].sphere.center: required key is missing");
  j = scene_with_obstacles();
  j["obstacles"][0]["sphere"]["centre"] = j["obstacles"][0]["sphere"]["center"];
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: obstacles[0].sphere.centre: unknown key; did you mean 'center'?");
}

TEST(ObstacleScene, BadPlane) {
  Json j = scene_with_obstacles();
  j["obstacles"][1]["plane"]["normal"] = {0, 0, 2};
  EXPECT_EQ(scene_error_of(j),
            "scene.json: obstacles[1].plane.normal: expected a unit vector, got [0, 0, 2] "
            "(length 2)");
  j["obstacles"][1]["plane"]["normal"] = {0, 0, 0};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].plane.normal: expected a unit vector");
  j["obstacles"][1]["plane"].erase("normal");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].plane.normal: required key is missing");
  j = scene_with_obstacles();
  j["obstacles"][1]["plane"].erase("point");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].plane.point: required key is missing");
  j = scene_with_obstacles();
  j["obstacles"][1]["plane"]["point"] = {0, "1 s", 0};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].plane.point[1]: expected a length");
}

// The box, cylinder and capsule of docs/scene.md, with units.
Json scene_with_shapes() {
  Json j = scene_with_obstacles();
  j["obstacles"] = Json::parse(R"([
    {"box": {"center": [0, 0, "5 cm"], "half_size": ["5 cm", "4 cm", "50 mm"], "yaw": 30}},
    {"cylinder": {"center": ["1 m", 0, "20 cm"], "axis": [0, 0, 1], "radius": "9 cm",
                  "height": "1 cm"}},
    {"capsule": {"a": [0, "-10 cm", "30 cm"], "b": [0, "10 cm", "30 cm"], "radius": "3 cm"}}
  ])");
  return j;
}

TEST(ObstacleScene, BoxCylinderAndCapsuleLandInSIUnits) {
  const Scene s = parse_json_scene(scene_with_shapes());
  ASSERT_EQ(s.sim.obstacles.size(), 3u);
  const auto& box = std::get<sim::BoxObstacle>(s.sim.obstacles[0]);
  EXPECT_TRUE(box.center_m.isApprox(Eigen::Vector3d(0, 0, 0.05), 1e-15));
  EXPECT_TRUE(box.half_size_m.isApprox(Eigen::Vector3d(0.05, 0.04, 0.05), 1e-15));
  EXPECT_NEAR(box.yaw_rad, base::kPi / 6.0, 1e-15);  // a bare angle is degrees
  const auto& cylinder = std::get<sim::CylinderObstacle>(s.sim.obstacles[1]);
  EXPECT_TRUE(cylinder.center_m.isApprox(Eigen::Vector3d(1.0, 0, 0.2), 1e-15));
  EXPECT_EQ(cylinder.axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_NEAR(cylinder.radius_m, 0.09, 1e-15);
  EXPECT_NEAR(cylinder.height_m, 0.01, 1e-15);
  const auto& capsule = std::get<sim::CapsuleObstacle>(s.sim.obstacles[2]);
  EXPECT_TRUE(capsule.a_m.isApprox(Eigen::Vector3d(0, -0.1, 0.3), 1e-15));
  EXPECT_TRUE(capsule.b_m.isApprox(Eigen::Vector3d(0, 0.1, 0.3), 1e-15));
  EXPECT_NEAR(capsule.radius_m, 0.03, 1e-15);
  // Yaw defaults to 0; each shape is drawn, in the obstacle colour.
  Json j = scene_with_shapes();
  j["obstacles"][0]["box"].erase("yaw");
  EXPECT_EQ(std::get<sim::BoxObstacle>(parse_json_scene(j).sim.obstacles[0]).yaw_rad, 0.0);
  EXPECT_EQ(obstacle_render_objects(s.sim.obstacles, s.render).size(), 3u);
}

TEST(ObstacleScene, BadBoxCylinderAndCapsule) {
  Json j = scene_with_shapes();
  j["obstacles"][0]["box"]["half_size"] = {"5 cm", 0, "5 cm"};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].box.half_size[1]: expected a length > 0");
  j["obstacles"][0]["box"]["half_size"] = {"5 cm", "5 cm"};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].box.half_size: expected an array of 3");
  j["obstacles"][0]["box"].erase("half_size");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].box.half_size: required key is missing");
  j = scene_with_shapes();
  j["obstacles"][0]["box"]["yaw"] = "30 cm";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].box.yaw: expected an angle");
  j = scene_with_shapes();
  j["obstacles"][0]["box"]["size"] = 1;
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[0].box.size: unknown key");
  j = scene_with_shapes();
  j["obstacles"][1]["cylinder"]["axis"] = {0, 0, 2};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].cylinder.axis: expected a unit vector");
  j = scene_with_shapes();
  j["obstacles"][1]["cylinder"]["height"] = "-1 cm";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].cylinder.height: expected a length > 0");
  j = scene_with_shapes();
  j["obstacles"][1]["cylinder"].erase("radius");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[1].cylinder.radius: required key is missing");
  j = scene_with_shapes();
  j["obstacles"][2]["capsule"]["radius"] = 0;
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[2].capsule.radius: expected a length > 0");
  j = scene_with_shapes();
  j["obstacles"][2]["capsule"]["b"] = {0, "1 kg", 0};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[2].capsule.b[1]: expected a length");
  j = scene_with_shapes();
  j["obstacles"][2]["capsule"].erase("a");
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: obstacles[2].capsule.a: required key is missing");
}

TEST(ObstacleScene, PedestalDrapeAssetParses) {
  const Scene s = load_scene(std::filesystem::path(WEFT_SOURCE_DIR) / "assets" / "scenes" /
                             "pedestal_drape.json");
  EXPECT_NE(s.description.find("Kang & Yu"), std::string::npos);
  EXPECT_NE(s.description.find("seed 002"), std::string::npos);
  ASSERT_EQ(s.sim.obstacles.size(), 2u);
  const auto& pedestal = std::get<sim::BoxObstacle>(s.sim.obstacles[0]);
  // A 10 × 10 cm pedestal standing on the ground; a 20 × 20 cm sheet centred above it.
  EXPECT_NEAR(2.0 * pedestal.half_size_m.x(), 0.10, 1e-12);
  EXPECT_NEAR(2.0 * pedestal.half_size_m.y(), 0.10, 1e-12);
  EXPECT_NEAR(pedestal.center_m.z() - pedestal.half_size_m.z(), 0.0, 1e-12);
  EXPECT_NEAR(s.grid.size_u_m, 0.20, 1e-12);
  EXPECT_NEAR(s.grid.size_v_m, 0.20, 1e-12);
  EXPECT_NEAR(s.grid.origin.x() + 0.5 * s.grid.size_u_m, pedestal.center_m.x(), 1e-12);
  EXPECT_NEAR(s.grid.origin.y() + 0.5 * s.grid.size_v_m, pedestal.center_m.y(), 1e-12);
  EXPECT_GT(s.grid.origin.z(), pedestal.center_m.z() + pedestal.half_size_m.z());
  // The rendered ground is not drawn again: only the pedestal.
  EXPECT_EQ(obstacle_render_objects(s.sim.obstacles, s.render).size(), 1u);
}

TEST(ObstacleScene, BadThicknessAndColour) {
  Json j = scene_with_obstacles();
  j["simulation"]["collision_thickness"] = "-1 mm";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: simulation.collision_thickness: expected a length ≥ 0");
  j["simulation"]["collision_thickness"] = "1 s";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: simulation.collision_thickness: expected a length");
  j = scene_with_obstacles();
  j["render"]["colors"]["obstacle"] = {0.5, 1.5, 0.5};
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: render.colors.obstacle[1]: expected a number in [0, 1]");
}

TEST(ObstacleScene, SphereDrapeAssetParses) {
  const Scene s = load_scene(std::filesystem::path(WEFT_SOURCE_DIR) / "assets" / "scenes" /
                             "sphere_drape.json");
  EXPECT_EQ(s.name, "sphere_drape");
  EXPECT_NE(s.description.find("4.5"), std::string::npos);
  EXPECT_TRUE(s.pins.empty());
  ASSERT_EQ(s.sim.obstacles.size(), 2u);
  const auto& sphere = std::get<sim::SphereObstacle>(s.sim.obstacles[0]);
  EXPECT_EQ(sphere.center_m, Eigen::Vector3d(0, 0, 0.6));
  EXPECT_EQ(sphere.radius_m, 0.25);
  // The sheet starts flat, centred over the sphere, 2 cm above its top.
  EXPECT_NEAR(s.grid.origin.z() - (sphere.center_m.z() + sphere.radius_m), 0.02, 1e-12);
  EXPECT_NEAR(s.grid.origin.x() + 0.5 * s.grid.size_u_m, 0.0, 1e-12);
  EXPECT_NEAR(s.grid.origin.y() + 0.5 * s.grid.size_v_m, 0.0, 1e-12);
  const auto& ground = std::get<sim::PlaneObstacle>(s.sim.obstacles[1]);
  EXPECT_EQ(ground.normal, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(ground.point_m.z(), s.render.ground_z_m);
  // Friction holds the drape on the sphere (without it the sheet slides off, docs/scene.md).
  EXPECT_EQ(s.sim.collision_friction, 0.5);
  // The ground plane is the rendered ground: only the sphere is drawn as an object.
  EXPECT_EQ(obstacle_render_objects(s.sim.obstacles, s.render).size(), 1u);
}

TEST(ObstacleMeshes, SphereAtItsTrueRadiusInTheObstacleColour) {
  render::RenderSettings settings;
  settings.obstacle_color = {0.1f, 0.2f, 0.3f};
  const sim::SphereObstacle sphere{{0.0, 0.0, 0.6}, 0.25};
  const auto objects = obstacle_render_objects({sphere}, settings);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].color, settings.obstacle_color);
  ASSERT_FALSE(objects[0].mesh.positions.empty());
  for (const Eigen::Vector3f& p : objects[0].mesh.positions)
    EXPECT_NEAR((p.cast<double>() - sphere.center_m).norm(), 0.25, 1e-6);
}

TEST(ObstacleMeshes, GroundPlaneIsSkippedOtherPlanesArePatches) {
  render::RenderSettings settings;  // ground on at z = 0
  settings.camera.target = {0.3, 0.2, 0.5};
  const sim::PlaneObstacle ground{{5.0, -3.0, 0.0}, {0.0, 0.0, 1.0}};
  EXPECT_TRUE(obstacle_render_objects({ground}, settings).empty());

  // Not the rendered ground: a different height, no ground drawn, or tilted.
  settings.ground_z_m = -0.01;
  ASSERT_EQ(obstacle_render_objects({ground}, settings).size(), 1u);
  settings.ground_z_m = 0.0;
  settings.ground = false;
  ASSERT_EQ(obstacle_render_objects({ground}, settings).size(), 1u);
  settings.ground = true;

  const sim::PlaneObstacle wall{{1.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}};
  const auto objects = obstacle_render_objects({wall, ground}, settings);
  ASSERT_EQ(objects.size(), 1u);
  const render::RenderMesh& patch = objects[0].mesh;
  ASSERT_EQ(patch.positions.size(), 4u);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(patch.positions[v].x(), 1.0f, 1e-6f);  // in the plane x = 1
    EXPECT_TRUE(patch.normals[v].isApprox(Eigen::Vector3f(-1, 0, 0)));
    mean += patch.positions[v].cast<double>() / 4.0;
  }
  // Centred on the point of the plane nearest the camera target, 4 m wide.
  EXPECT_TRUE(mean.isApprox(Eigen::Vector3d(1.0, 0.2, 0.5), 1e-6));
  EXPECT_NEAR((patch.positions[0] - patch.positions[2]).norm(),
              static_cast<float>(4.0 * std::sqrt(2.0)), 1e-5f);
}

}  // namespace
}  // namespace weft::app
