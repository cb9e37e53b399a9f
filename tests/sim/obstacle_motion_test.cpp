// Keyframed obstacle motion: interpolation, posing every obstacle kind rigidly, friction
// relative to a moving surface, and a cloth carried by a moving plate.

#include "sim/collision/obstacle_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "base/constants.h"
#include "sim/simulator.h"
#include "test_cloth.h"

namespace weft::sim {
namespace {

ObstacleMotion two_keys() {
  return ObstacleMotion({{1.0, Vec3(0.0, 0.0, 0.0), 0.0}, {3.0, Vec3(0.2, -0.4, 0.6), base::kPi / 2}});
}

TEST(ObstacleMotion, HoldsBeforeTheFirstAndAfterTheLastKeyAndIsLinearBetween) {
  const ObstacleMotion m = two_keys();
  EXPECT_TRUE(m.moves());
  EXPECT_EQ(m.pose_at(-5.0).translation_m, Vec3::Zero());
  EXPECT_EQ(m.pose_at(1.0).yaw_rad, 0.0);
  const RigidPose mid = m.pose_at(2.5);  // three quarters of the way
  EXPECT_TRUE(mid.translation_m.isApprox(Vec3(0.15, -0.3, 0.45), 1e-15));
  EXPECT_NEAR(mid.yaw_rad, 0.75 * base::kPi / 2, 1e-15);
  EXPECT_EQ(m.pose_at(3.0).translation_m, Vec3(0.2, -0.4, 0.6));
  EXPECT_EQ(m.pose_at(100.0).yaw_rad, base::kPi / 2);
  // Three keys: each segment on its own.
  const ObstacleMotion three({{0.0, Vec3::Zero(), 0.0},
                              {1.0, Vec3(1, 0, 0), 0.0},
                              {2.0, Vec3(1, 2, 0), 0.0}});
  EXPECT_TRUE(three.pose_at(0.5).translation_m.isApprox(Vec3(0.5, 0, 0)));
  EXPECT_TRUE(three.pose_at(1.25).translation_m.isApprox(Vec3(1, 0.5, 0)));
  EXPECT_FALSE(ObstacleMotion().moves());
  EXPECT_EQ(ObstacleMotion().pose_at(3.0).translation_m, Vec3::Zero());
}

TEST(ObstacleMotion, RejectsTimesThatDoNotIncreaseAndNonFiniteValues) {
  const auto message = [](std::vector<ObstacleKeyframe> keys) -> std::string {
    try {
      ObstacleMotion m(std::move(keys));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message({{1.0, Vec3::Zero(), 0.0}, {1.0, Vec3::Zero(), 0.0}})
                .find("keyframe 1: time 1 s is not after keyframe 0's 1 s"),
            std::string::npos);
  EXPECT_NE(message({{0.0, Vec3(0, std::nan(""), 0), 0.0}}).find("keyframe 0: translate"),
            std::string::npos);
  EXPECT_NE(message({{0.0, Vec3::Zero(), INFINITY}}).find("rotate_z"), std::string::npos);
  EXPECT_NE(message({{NAN, Vec3::Zero(), 0.0}}).find("keyframe 0: time nan s is not finite"), std::string::npos);
}

// Posing is rigid: the point moved with an obstacle keeps its signed distance, for every kind.
TEST(ObstacleMotion, PosedObstaclesKeepTheSignedDistanceOfPointsMovedWithThem) {
  Matrix3X v(4, 3);
  v << 0, 0, 0, 0.2, 0, 0, 0, 0.2, 0, 0, 0, 0.2;  // a tetrahedron
  const auto tetrahedron = std::make_shared<const MeshSolid>(
      v, std::vector<std::array<Index, 3>>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  const std::vector<Obstacle> obstacles{
      SphereObstacle{Vec3(0.1, 0.2, 0.3), 0.1},
      PlaneObstacle{Vec3(0, 0, 0.1), Vec3(0.6, 0.0, 0.8)},
      BoxObstacle{Vec3(0.3, 0.1, 0.0), Vec3(0.1, 0.2, 0.05), 0.4},
      CylinderObstacle{Vec3(-0.2, 0.1, 0.1), Vec3(0.0, 0.6, 0.8), 0.1, 0.05},
      CapsuleObstacle{Vec3(0, 0, 0), Vec3(0.1, 0.2, 0.3), 0.05},
      MeshObstacle{tetrahedron, RigidPose{Vec3(0.1, 0, 0), 0.3}}};
  const RigidPose pose{Vec3(0.5, -0.3, 0.2), 1.1};
  const Vec3 probes[] = {Vec3(0.12, 0.18, 0.31), Vec3(0.4, -0.2, 0.3), Vec3(-0.1, 0.05, 0.12),
                         Vec3(0.15, 0.05, 0.04)};
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle moved = posed(obstacles[k], pose);
    for (const Vec3& x : probes)
      EXPECT_NEAR(signed_distance(moved, pose.apply(x)), signed_distance(obstacles[k], x), 1e-14)
          << "obstacle " << k;
  }
  // Without motions (or with empty ones) obstacles stay where they are.
  const auto same = posed_obstacles(obstacles, {}, 1.0);
  EXPECT_EQ(std::get<SphereObstacle>(same[0]).center_m, Vec3(0.1, 0.2, 0.3));
  EXPECT_THROW(posed_obstacles(obstacles, {two_keys()}, 1.0), std::invalid_argument);
}

// motion_between carries a point fixed to the obstacle along: it keeps its place on it.
TEST(ObstacleMotion, MotionBetweenCarriesAPointFixedToTheObstacle) {
  const ObstacleMotion m = two_keys();
  const BoxObstacle box{Vec3(0.3, 0.0, 0.0), Vec3(0.1, 0.1, 0.1), 0.0};
  const Vec3 x(0.35, 0.12, -0.05);
  const Obstacle at_t0 = posed(box, m.pose_at(1.5)), at_t1 = posed(box, m.pose_at(2.25));
  const Vec3 carried = m.motion_between(1.5, 2.25).apply(x);
  EXPECT_NEAR(signed_distance(at_t1, carried), signed_distance(at_t0, x), 1e-14);
  EXPECT_NEAR(signed_distance(std::get<BoxObstacle>(at_t1), carried),
              signed_distance(std::get<BoxObstacle>(at_t0), x), 1e-14);
}

// A vertex resting on a plate that turns about z: with friction it is dragged towards where its
// start point went with the plate, by at most friction × the push-out depth (Coulomb).
TEST(ObstacleMotion, FrictionDragsTowardsTheStartCarriedByTheSurface) {
  const std::vector<Obstacle> plate{BoxObstacle{Vec3(0, 0, -0.01), Vec3(1, 1, 0.01), 0.0}};
  const double t = 0.002, depth = 1e-4, turn = 0.01;  // m, m, rad over the step
  const std::vector<RigidPose> motion{RigidPose{Vec3::Zero(), turn}};
  Matrix3X start(1, 3), x(1, 3);
  start << 0.5, 0.0, t;
  x << 0.5, 0.0, t - depth;  // it did not move sideways; gravity sank it by `depth`
  const Vec3 start_point = start.row(0).transpose();
  const Vec3 carried = motion[0].apply(start_point);  // 5 mm along +y
  const Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(1);
  Matrix3X kinetic = x, sticking = x, still = x;
  (void)push_out_of_obstacles(plate, motion, t, inv_mass, start, 1.0, kinetic);
  // Dragged by friction × depth (μ = 1) towards the carried start, and back on the surface.
  const Vec3 dragged = kinetic.row(0).transpose() - start_point;
  EXPECT_LT((dragged - depth * (carried - start_point).normalized()).norm(), 1e-12);
  EXPECT_NEAR(kinetic(0, 2), t, 1e-12);
  (void)push_out_of_obstacles(plate, motion, t, inv_mass, start, 100.0, sticking);
  EXPECT_NEAR(sticking(0, 0), carried.x(), 1e-12);  // sticks: goes round with the plate
  EXPECT_NEAR(sticking(0, 1), carried.y(), 1e-12);
  (void)push_out_of_obstacles(plate, {}, t, inv_mass, start, 100.0, still);  // plate at rest
  EXPECT_NEAR(still(0, 1), 0.0, 1e-15);
}

// A 20 cm cloth lying on a plate that slides 10 cm along x in 0.5 s and stops (0.2 m/s).
// With μ = 1 friction accelerates the cloth at up to μg, so it lags by v²/(2μg) = 2 mm while
// catching up and slides as far past the stop: it ends 10 cm along, carried. Without friction
// nothing pulls it sideways: it stays.
double cloth_carried_by_plate(double friction, double* lag_m) {
  const double thickness = 0.002;
  GridSpec grid;
  grid.size_u_m = grid.size_v_m = 0.2;
  grid.nu = grid.nv = 9;
  grid.origin = Vec3(-0.1, -0.1, thickness);
  SimSettings s;
  s.air_damping_1_s = 0.0;
  s.collision_thickness_m = thickness;
  s.collision_friction = friction;
  s.obstacles = {BoxObstacle{Vec3(0, 0, -0.01), Vec3(0.5, 0.5, 0.01), 0.0}};
  s.obstacle_motions = {ObstacleMotion({{0.1, Vec3::Zero(), 0.0}, {0.6, Vec3(0.1, 0, 0), 0.0}})};
  Simulator sim(make_grid(grid), test_cloth::fabric(200.0), {}, s);
  const auto com_x = [&] {
    return sim.masses_kg().dot(sim.state().x.col(0)) / sim.masses_kg().sum();
  };
  sim.advance(0.35);  // plate half-way: 5 cm along, moving
  *lag_m = 0.05 - com_x();
  sim.advance(0.45);
  for (Index i = 0; i < sim.mesh().vertex_count(); ++i)
    EXPECT_GE(sim.state().x(i, 2), thickness - 1e-9);  // never through the plate
  return com_x();
}

TEST(ObstacleMotion, ClothOnASlidingPlateMovesWithItWithFrictionAndStaysWithout) {
  double lag_with = 0.0, lag_without = 0.0;
  const double carried = cloth_carried_by_plate(1.0, &lag_with);
  const double left = cloth_carried_by_plate(0.0, &lag_without);
  std::printf("plate moved 100 mm: cloth moved %.2f mm with mu 1 (lag %.2f mm while moving), "
              "%.3f mm with mu 0\n", 1e3 * carried, 1e3 * lag_with, 1e3 * left);
  const double expected_lag = 0.2 * 0.2 / (2.0 * 1.0 * 9.81);  // v²/(2μg) = 2.0 mm
  EXPECT_NEAR(lag_with, expected_lag, 0.5e-3);
  EXPECT_NEAR(carried, 0.1, 1e-3);
  EXPECT_NEAR(left, 0.0, 1e-6);
  EXPECT_NEAR(lag_without, 0.05, 1e-6);
}

TEST(ObstacleMotion, SimulatorRejectsMotionsThatDoNotMatchTheObstacles) {
  SimSettings s;
  s.obstacles = {PlaneObstacle{}};
  s.obstacle_motions = {ObstacleMotion(), ObstacleMotion()};
  EXPECT_THROW(Simulator(test_cloth::square(3), test_cloth::fabric(100.0), {}, s),
               std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
