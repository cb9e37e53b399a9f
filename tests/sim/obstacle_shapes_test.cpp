// Box, cylinder and capsule obstacles (sim/collision/obstacle_shapes.h): exact signed distances
// against hand-computed values inside, outside and at edges, corners and rims; the closest
// surface point's normal is the finite-difference gradient of the signed distance; push-out
// leaves every vertex at the thickness; Coulomb friction on a box top; check_obstacles names
// the obstacle; and a small cloth dropped on a pedestal ends outside it.

#include "sim/collision/obstacle_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/constants.h"
#include "sim/collision/obstacle.h"
#include "sim/simulator.h"
#include "tests/sim/test_cloth.h"

namespace weft::sim {
namespace {
constexpr double tol_m = 1e-12;  // m

// A turned box off the origin and its world point from local coordinates (its x, y, z axes).
const BoxObstacle tilted_box{Vec3(0.1, -0.2, 0.3), Vec3(0.05, 0.1, 0.02), base::kPi / 6.0};
Vec3 box_point(double x, double y, double z) {
  return tilted_box.center_m + x * box_axis_x(tilted_box) + y * box_axis_y(tilted_box) +
         z * Vec3::UnitZ();
}

// A tilted disc (radius 9 cm, 2 cm high) and a world point from its axial coordinates.
const CylinderObstacle disc{Vec3(-0.1, 0.2, 0.05), Vec3(0.3, 0.0, 1.0).normalized(), 0.09, 0.02};
Vec3 disc_point(double r, double z, double azimuth) {
  const Vec3 e1 = disc.axis.unitOrthogonal(), e2 = disc.axis.cross(e1);
  return disc.center_m + z * disc.axis + r * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2);
}

const CapsuleObstacle capsule{Vec3(0.0, 0.0, 0.1), Vec3(0.0, 0.2, 0.1), 0.05};

TEST(ObstacleShapes, BoxSignedDistanceMatchesHandValues) {
  struct Case {
    Vec3 local;
    double expected_m;
  };
  const Case cases[] = {
      {{0.0, 0.0, 0.0}, -0.02},                     // centre: the z faces are nearest
      {{0.04, 0.0, 0.0}, -0.01},                    // inside, 1 cm from the +x face
      {{-0.045, 0.05, -0.01}, -0.005},              // inside, 5 mm from the −x face
      {{0.0, -0.095, 0.0}, -0.005},                 // inside, near the −y face
      {{0.05, 0.0, 0.0}, 0.0},                      // on the +x face
      {{0.08, 0.0, 0.01}, 0.03},                    // outside the +x face
      {{0.0, 0.0, -0.07}, 0.05},                    // below the bottom
      {{0.08, 0.14, 0.0}, std::hypot(0.03, 0.04)},  // beyond an edge
      {{-0.08, -0.13, 0.06}, std::sqrt(0.03 * 0.03 * 2 + 0.0016)},  // beyond a corner
      {{0.05, 0.1, 0.02}, 0.0},                                     // at a corner
  };
  for (const Case& c : cases) {
    const Vec3 p = box_point(c.local.x(), c.local.y(), c.local.z());
    EXPECT_NEAR(signed_distance(tilted_box, p), c.expected_m, tol_m) << c.local.transpose();
    EXPECT_NEAR(signed_distance(Obstacle{tilted_box}, p), c.expected_m, tol_m);
  }
}

TEST(ObstacleShapes, CylinderSignedDistanceMatchesHandValues) {
  struct Case {
    double r, z, expected_m;
  };
  const Case cases[] = {
      {0.0, 0.0, -0.01},                      // centre: the caps are nearest
      {0.085, 0.0, -0.005},                   // inside, near the side
      {0.03, -0.008, -0.002},                 // inside, near the bottom cap
      {0.12, 0.005, 0.03},                    // beside the side
      {0.05, 0.04, 0.03},                     // above the top cap
      {0.0, -0.03, 0.02},                     // below, on the axis
      {0.12, 0.05, 0.05},                     // beyond the top rim: 3-4-5
      {0.15, -0.09, std::hypot(0.06, 0.08)},  // beyond the bottom rim
      {0.09, 0.01, 0.0},                      // on the rim
  };
  for (const Case& c : cases) {
    for (const double azimuth : {0.0, 1.0, 4.0}) {
      const Vec3 p = disc_point(c.r, c.z, azimuth);
      EXPECT_NEAR(signed_distance(disc, p), c.expected_m, tol_m) << c.r << " " << c.z;
    }
  }
}

TEST(ObstacleShapes, CapsuleSignedDistanceMatchesHandValues) {
  EXPECT_NEAR(signed_distance(capsule, Vec3(0.1, 0.1, 0.1)), 0.05, tol_m);    // beside
  EXPECT_NEAR(signed_distance(capsule, Vec3(0.0, 0.3, 0.1)), 0.05, tol_m);    // beyond b
  EXPECT_NEAR(signed_distance(capsule, Vec3(0.03, -0.04, 0.1)), 0.0, tol_m);  // on a's cap
  EXPECT_NEAR(signed_distance(capsule, Vec3(0.0, 0.05, 0.1)), -0.05, tol_m);  // on the axis
  EXPECT_NEAR(signed_distance(capsule, Vec3(0.0, 0.15, 0.13)), -0.02, tol_m);
  const CapsuleObstacle ball{Vec3(1, 2, 3), Vec3(1, 2, 3), 0.5};  // a = b: a sphere
  EXPECT_NEAR(signed_distance(ball, Vec3(1, 2, 4)), 0.5, tol_m);
}

// Finite differences of the signed distance against the closest surface point's normal, and
// the closest point's own distance (0) and offset (p − point = sd·normal), at random points
// inside and outside. Points whose difference stencil straddles a kink of the distance (the
// medial surface inside, the edges at the surface) are recognised by their neighbours' normals
// disagreeing, and skipped; at least 90 % must be checked.
template <class Shape>
void expect_normal_is_gradient(const Shape& shape, const Vec3& lo, const Vec3& hi) {
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double h = 1e-7;
  const int count = 2000;
  int checked = 0;
  for (int k = 0; k < count; ++k) {
    const Vec3 p =
        lo + Vec3(unit(generator), unit(generator), unit(generator)).cwiseProduct(hi - lo);
    const SurfacePoint q = closest_surface_point(shape, p);
    const double sd = signed_distance(shape, p);
    EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
    EXPECT_NEAR(signed_distance(shape, q.point_m), 0.0, 1e-12);
    EXPECT_LT((p - q.point_m - sd * q.normal).norm(), 1e-12) << p.transpose();
    Vec3 gradient;
    bool smooth = true;
    for (int i = 0; i < 3; ++i) {
      const Vec3 step = h * Vec3::Unit(i);
      smooth = smooth && (closest_surface_point(shape, p + step).normal - q.normal).norm() < 1e-3 &&
               (closest_surface_point(shape, p - step).normal - q.normal).norm() < 1e-3;
      gradient[i] = (signed_distance(shape, p + step) - signed_distance(shape, p - step)) / (2 * h);
    }
    if (!smooth) continue;
    ++checked;
    EXPECT_LT((gradient - q.normal).norm(), 1e-6)
        << "at " << p.transpose() << ": finite differences " << gradient.transpose() << ", normal "
        << q.normal.transpose();
  }
  EXPECT_GE(checked, count * 9 / 10);
}

TEST(ObstacleShapes, NormalIsTheFiniteDifferenceGradientOfTheSignedDistance) {
  expect_normal_is_gradient(tilted_box, tilted_box.center_m - Vec3(0.15, 0.15, 0.08),
                            tilted_box.center_m + Vec3(0.15, 0.15, 0.08));
  expect_normal_is_gradient(disc, disc.center_m - Vec3(0.15, 0.15, 0.06),
                            disc.center_m + Vec3(0.15, 0.15, 0.06));
  expect_normal_is_gradient(capsule, Vec3(-0.1, -0.1, 0.0), Vec3(0.1, 0.3, 0.2));
}

// Inside: out through the nearest face, cap or side, at its outward normal.
TEST(ObstacleShapes, InsidePointsLeaveThroughTheNearestFace) {
  SurfacePoint q = closest_surface_point(tilted_box, box_point(0.01, 0.09, 0.0));
  EXPECT_LT((q.point_m - box_point(0.01, 0.1, 0.0)).norm(), tol_m);
  EXPECT_LT((q.normal - box_axis_y(tilted_box)).norm(), tol_m);
  q = closest_surface_point(tilted_box, box_point(0.01, 0.0, -0.015));
  EXPECT_LT((q.normal + Vec3::UnitZ()).norm(), tol_m);
  q = closest_surface_point(disc, disc_point(0.085, 0.002, 2.0));
  EXPECT_LT((q.point_m - disc_point(0.09, 0.002, 2.0)).norm(), tol_m);
  q = closest_surface_point(disc, disc_point(0.02, 0.006, 2.0));
  EXPECT_LT((q.point_m - disc_point(0.02, 0.01, 2.0)).norm(), tol_m);
  EXPECT_LT((q.normal - disc.axis).norm(), tol_m);
}

// 500 random vertices within ±spread_m (per axis) of `centre`, pushed out of the one shape with a 3
// mm thickness: those already clear are left bit-for-bit, the others land exactly on the offset
// surface, moved along the normal at their closest surface point.
template <class Shape>
void expect_push_out_to_thickness(const Shape& shape, const Vec3& centre, const Vec3& spread_m,
                                  unsigned seed) {
  const double t = 0.003;
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Matrix3X x(500, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    x.row(i) =
        (centre + spread_m.cwiseProduct(Vec3(unit(generator), unit(generator), unit(generator))))
            .transpose();
  const Matrix3X before = x;
  const int moved = push_out_of_obstacles({shape}, t, Eigen::VectorXd::Ones(x.rows()), x);
  int expected_moved = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const Vec3 p0 = before.row(i).transpose(), p = x.row(i).transpose();
    const double d0 = signed_distance(shape, p0);
    if (d0 >= t) {
      EXPECT_EQ(p, p0);
      continue;
    }
    ++expected_moved;
    EXPECT_NEAR(signed_distance(shape, p), t, 1e-12) << p0.transpose();
    const Vec3 n = closest_surface_point(shape, p0).normal;
    EXPECT_LT((p - p0 - (t - d0) * n).norm(), 1e-12) << p0.transpose();
  }
  EXPECT_EQ(moved, expected_moved);
  EXPECT_GT(moved, 50);
}

TEST(ObstacleShapes, PushOutLeavesEveryVertexAtTheThickness) {
  expect_push_out_to_thickness(tilted_box, tilted_box.center_m, Vec3(0.1, 0.15, 0.04), 11);
  expect_push_out_to_thickness(disc, disc.center_m, Vec3(0.12, 0.12, 0.04), 12);
  expect_push_out_to_thickness(capsule, Vec3(0.0, 0.1, 0.1), Vec3(0.08, 0.2, 0.08), 13);
}

// A box pedestal and a cylinder standing on the ground plane: vertices in the concave wedge
// where their sides meet the ground end clear of both.
TEST(ObstacleShapes, PedestalOnTheGroundClearsTheWedge) {
  const double t = 0.002;
  const BoxObstacle pedestal{Vec3(0, 0, 0.05), Vec3(0.05, 0.05, 0.05), 0.3};
  const CylinderObstacle support{Vec3(0.3, 0, 0.05), Vec3::UnitZ(), 0.09, 0.1};
  const std::vector<Obstacle> obstacles = {PlaneObstacle{Vec3::Zero(), Vec3::UnitZ()}, pedestal,
                                           support};
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Around each foot, 1 mm under to 3 mm over the ground, never under the pedestal itself (a
  // pocket with no way out).
  Matrix3X x(400, 3);
  for (Eigen::Index i = 0; i < x.rows();) {
    const Obstacle& foot = obstacles[1 + i % 2];
    const Vec3 base(i % 2 == 0 ? 0.0 : 0.3, 0.0, 0.0);
    const double azimuth = 2 * base::kPi * unit(generator), r = 0.03 + 0.08 * unit(generator);
    const double z = -0.001 + 0.004 * unit(generator);
    const Vec3 p = base + Vec3(r * std::cos(azimuth), r * std::sin(azimuth), z);
    if (signed_distance(foot, Vec3(p.x(), p.y(), 0.05)) <= 0.0) continue;  // under the foot
    x.row(i++) = p.transpose();
  }
  push_out_of_obstacles(obstacles, t, Eigen::VectorXd::Ones(x.rows()), x);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (const Obstacle& o : obstacles)
      EXPECT_GE(signed_distance(o, x.row(i).transpose()), t - 1e-12) << x.row(i);
}

// A vertex sliding on a (turned) box top: its predicted position 2 mm into the top and 1 mm
// along it. μ = 1 ≥ slide/depth sticks it; μ = 0 lets it slide the full 1 mm; μ = 0.25 shortens
// the slide by μ·depth = 0.5 mm.
TEST(ObstacleShapes, FrictionStopsAVertexSlidingOnABoxTop) {
  const double t = 0.002;
  const std::vector<Obstacle> obstacles = {tilted_box};
  const Vec3 start = box_point(0.0, 0.0, 0.02 + t);
  const Vec3 along = (box_axis_x(tilted_box) + box_axis_y(tilted_box)).normalized();
  const Matrix3X x_start = start.transpose();
  const Matrix3X predicted = (start + 0.001 * along - 0.002 * Vec3::UnitZ()).transpose();
  const Eigen::VectorXd free = Eigen::VectorXd::Ones(1);
  const std::pair<double, double> cases[] = {{1.0, 0.0}, {0.0, 0.001}, {0.25, 0.0005}};
  for (const auto& [mu, slide_m] : cases) {
    Matrix3X x = predicted;
    EXPECT_EQ(push_out_of_obstacles(obstacles, t, free, x_start, mu, x), 1);
    const Vec3 expected = start + slide_m * along;
    EXPECT_LT((x.row(0).transpose() - expected).norm(), 1e-12) << "mu " << mu << ": " << x;
  }
}

TEST(ObstacleShapes, CheckObstaclesNamesTheObstacleAndTheProblem) {
  const auto error_of = [](const Obstacle& bad) {
    try {
      check_obstacles({SphereObstacle{}, bad});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(BoxObstacle{Vec3::Zero(), Vec3(0.1, 0.0, 0.1), 0.0}),
            "obstacle 1: box half size y must be finite and > 0, got 0.000000 m");
  EXPECT_EQ(error_of(BoxObstacle{Vec3(0, NAN, 0), Vec3::Ones(), 0.0}),
            "obstacle 1: box centre must be finite");
  EXPECT_EQ(error_of(BoxObstacle{Vec3::Zero(), Vec3::Ones(), INFINITY}),
            "obstacle 1: box yaw must be finite");
  EXPECT_EQ(error_of(CylinderObstacle{Vec3::Zero(), Vec3(0, 0, 2), 0.1, 0.1}),
            "obstacle 1: cylinder axis must be a unit vector, got length 2.000000");
  EXPECT_EQ(error_of(CylinderObstacle{Vec3::Zero(), Vec3::UnitZ(), -0.1, 0.1}),
            "obstacle 1: cylinder radius must be finite and > 0, got -0.100000 m");
  EXPECT_EQ(error_of(CylinderObstacle{Vec3::Zero(), Vec3::UnitZ(), 0.1, 0.0}),
            "obstacle 1: cylinder height must be finite and > 0, got 0.000000 m");
  EXPECT_EQ(error_of(CapsuleObstacle{Vec3::Zero(), Vec3(INFINITY, 0, 0), 0.1}),
            "obstacle 1: capsule endpoints must be finite");
  EXPECT_EQ(error_of(CapsuleObstacle{Vec3::Zero(), Vec3::UnitX(), 0.0}),
            "obstacle 1: capsule radius must be finite and > 0, got 0.000000 m");
  EXPECT_EQ(error_of(tilted_box), "no error");
}

// 10×10 cm of cloth (9×9 vertices) dropped from 3 cm onto a 6×6 cm pedestal standing on the
// ground: after 0.4 s no vertex is inside the pedestal or the ground beyond the thickness, and
// the cloth's middle rests on the pedestal top.
TEST(ObstacleShapes, ClothDroppedOnAPedestalEndsOutsideIt) {
  SimSettings settings;
  settings.obstacles = {PlaneObstacle{Vec3::Zero(), Vec3::UnitZ()},
                        BoxObstacle{Vec3(0, 0, 0.025), Vec3(0.03, 0.03, 0.025), 0.2}};
  Simulator sim(test_cloth::square(9, 0.1, Vec3(-0.05, -0.05, 0.08)), test_cloth::fabric(200.0), {},
                settings);
  sim.advance(0.4);
  const double t = settings.collision_thickness_m;
  double lowest_middle = 1.0;
  for (Index i = 0; i < sim.mesh().vertex_count(); ++i) {
    const Vec3 p = sim.state().x.row(i).transpose();
    for (const Obstacle& o : settings.obstacles) EXPECT_GE(signed_distance(o, p), t - 1e-9);
    if (p.head<2>().norm() < 0.02) lowest_middle = std::min(lowest_middle, p.z());
  }
  EXPECT_NEAR(lowest_middle, 0.05 + t, 1e-3);
}

}  // namespace
}  // namespace weft::sim
