// What holds the cloth, drawn (app/run/support_meshes.h): clips on loose pins, a rod on a held
// edge reaching the ground when upright (a flag's pole), nothing for pins an obstacle holds,
// stems under floating spheres and discs, and none of it when render.supports is off.

#include "app/run/support_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "app/scene/scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

// The bounding box of an object's mesh.
Eigen::AlignedBox3f bounds(const render::RenderObject& object) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : object.mesh.positions) box.extend(p);
  return box;
}

sim::Matrix3X points(std::initializer_list<Eigen::Vector3d> list) {
  sim::Matrix3X x(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index row = 0;
  for (const Eigen::Vector3d& p : list) x.row(row++) = p.transpose();
  return x;
}

TEST(SupportMeshes, LoosePinsGetAClipEachAroundThePin) {
  const render::RenderSettings s;
  const sim::Matrix3X x = points({{0.0, 0.0, 1.0}, {0.5, 0.0, 1.0}, {0.2, 0.0, 0.6}});
  const auto objects = pin_support_objects({0, 1}, x, 0.01, {}, s);
  ASSERT_EQ(objects.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const Eigen::AlignedBox3f box = bounds(objects[k]);
    EXPECT_TRUE(box.contains(x.row(k).transpose().cast<float>())) << "clip " << k;
    EXPECT_LT(box.sizes().maxCoeff(), 0.05f);
    // Wide along the line to the other pin (x), narrow across it.
    EXPECT_GT(box.sizes().x(), 2.0f * box.sizes().y());
    EXPECT_EQ(objects[k].color, s.support_color);
  }
}

TEST(SupportMeshes, AnUprightHeldEdgeIsAPoleToTheGround) {
  render::RenderSettings s;
  s.ground_z_m = 0.1;
  const double edge = 0.02;
  sim::Matrix3X x(11, 3);
  for (int k = 0; k <= 10; ++k) x.row(k) << 0.3, 0.0, 1.0 + edge * k;  // a vertical edge
  std::vector<sim::Index> pinned;
  for (int k = 0; k <= 10; ++k) pinned.push_back(k);
  const auto pole = pin_support_objects(pinned, x, edge, {}, s);
  ASSERT_EQ(pole.size(), 1u);
  const Eigen::AlignedBox3f box = bounds(pole[0]);
  EXPECT_LE(box.min().z(), 0.1f + 1e-4f);  // reaches the ground
  EXPECT_GE(box.max().z(), 1.2f);           // and passes the top pin
  EXPECT_LT(box.sizes().x(), 0.03f);        // a thin rod

  // Lying horizontally, the held edge is a rod along it, off the ground.
  for (int k = 0; k <= 10; ++k) x.row(k) << edge * k, 0.0, 1.0;
  const auto rod = pin_support_objects(pinned, x, edge, {}, s);
  ASSERT_EQ(rod.size(), 1u);
  EXPECT_GT(bounds(rod[0]).min().z(), 0.9f);
  EXPECT_GT(bounds(rod[0]).sizes().x(), 0.2f);
}

TEST(SupportMeshes, PinsAnObstacleHoldsAndSupportsOffDrawNothing) {
  render::RenderSettings s;
  const std::vector<sim::Obstacle> disc{
      sim::CylinderObstacle{{0.0, 0.0, 0.3}, {0.0, 0.0, 1.0}, 0.09, 0.005}};
  const sim::Matrix3X on_disc = points({{0.0, 0.0, 0.3026}});
  EXPECT_TRUE(pin_support_objects({0}, on_disc, 0.01, disc, s).empty());
  s.supports = false;
  EXPECT_TRUE(pin_support_objects({0}, points({{0.0, 0.0, 1.0}}), 0.01, {}, s).empty());
  EXPECT_TRUE(stand_objects(disc, s).empty());
}

TEST(SupportMeshes, FloatingSpheresAndDiscsStandOnTheGround) {
  const render::RenderSettings s;  // ground at z = 0
  const std::vector<sim::Obstacle> floating{
      sim::SphereObstacle{{0.0, 0.0, 0.5}, 0.2},
      sim::CylinderObstacle{{1.0, 0.0, 0.3}, {0.0, 0.0, 1.0}, 0.09, 0.005}};
  const auto stands = stand_objects(floating, s);
  ASSERT_EQ(stands.size(), 4u);  // a stem and a foot each
  EXPECT_NEAR(bounds(stands[0]).min().z(), 0.0f, 1e-5f);
  EXPECT_GE(bounds(stands[0]).max().z(), 0.3f - 1e-5f);  // up to the sphere's bottom
  EXPECT_NEAR(bounds(stands[2]).max().z(), 0.2975f, 1e-5f);  // the disc's underside
  // Resting on the ground, or tilted: no stand.
  const std::vector<sim::Obstacle> resting{
      sim::SphereObstacle{{0.0, 0.0, 0.2}, 0.2},
      sim::CylinderObstacle{{1.0, 0.0, 0.3}, {1.0, 0.0, 0.0}, 0.09, 0.005}};
  EXPECT_TRUE(stand_objects(resting, s).empty());
}

TEST(SupportMeshes, SceneKeysTurnThemOffAndColourThem) {
  nlohmann::json scene = test::scene_with_render(
      nlohmann::json::parse(R"({"supports": false, "colors": {"support": [0.5, 0.4, 0.3]}})"));
  const Scene parsed = test::parse_json_scene(scene);
  EXPECT_FALSE(parsed.render.supports);
  EXPECT_EQ(parsed.render.support_color, Eigen::Vector3f(0.5f, 0.4f, 0.3f));
  EXPECT_TRUE(test::parse_json_scene(test::scene_with_render(nlohmann::json::object()))
                  .render.supports);
}

}  // namespace
}  // namespace weft::app
