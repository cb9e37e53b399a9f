// Obstacles: analytic signed distances, and the push-out invariants — every free vertex ends at
// least the thickness outside every obstacle, vertices already outside and pinned vertices do
// not move (bit-exact), moves go to the closest offset-surface point; at three scales. And
// Coulomb friction: static and kinetic cases by hand, the same invariants with it.

#include "sim/collision/obstacle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace weft::sim {
namespace {

constexpr double tolerance = 1e-12;  // metres, at unit scale

Matrix3X positions(const std::vector<Vec3>& points) {
  Matrix3X x(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) x.row(static_cast<Eigen::Index>(i)) = points[i];
  return x;
}

Eigen::VectorXd free_vertices(Eigen::Index n) {
  return Eigen::VectorXd::Ones(n);
}

// Uniform random points in the box [lo, hi], with an explicit seed.
std::vector<Vec3> random_points(int count, const Vec3& lo, const Vec3& hi, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const Vec3 f(unit(generator), unit(generator), unit(generator));
    points.push_back(lo + f.cwiseProduct(hi - lo));
  }
  return points;
}

// Every vertex with inv_mass > 0 is at least thickness − tol from every obstacle's surface.
::testing::AssertionResult all_clear(const std::vector<Obstacle>& obstacles, double thickness,
                                     const Matrix3X& x, double tol) {
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const double d = signed_distance(obstacles[k], x.row(i).transpose());
      if (!(d >= thickness - tol)) {
        return ::testing::AssertionFailure()
               << "vertex " << i << " at (" << x(i, 0) << ", " << x(i, 1) << ", " << x(i, 2)
               << ") is at distance " << d << " from obstacle " << k << " (thickness " << thickness
               << ")";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(Obstacle, SphereSignedDistanceIsAnalytic) {
  const Obstacle sphere = SphereObstacle{{1.0, -2.0, 0.5}, 0.25};
  EXPECT_DOUBLE_EQ(signed_distance(sphere, {1.0, -2.0, 0.5}), -0.25);  // centre
  EXPECT_DOUBLE_EQ(signed_distance(sphere, {1.0, -2.0, 0.75}), 0.0);   // on the surface
  EXPECT_DOUBLE_EQ(signed_distance(sphere, {1.0, -1.0, 0.5}), 0.75);   // outside
  EXPECT_DOUBLE_EQ(signed_distance(sphere, {1.1, -2.0, 0.5}), -0.15);  // inside
  EXPECT_DOUBLE_EQ(signed_distance(sphere, {1.3, -1.6, 0.5}), 0.25);   // 3-4-5
}

TEST(Obstacle, PlaneSignedDistanceIsAnalytic) {
  const Obstacle ground = PlaneObstacle{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  EXPECT_EQ(signed_distance(ground, {3.0, -4.0, 0.2}), 0.2);
  EXPECT_EQ(signed_distance(ground, {3.0, -4.0, -0.2}), -0.2);
  // Tilted plane through (1, 0, 0) with normal (1, 1, 0)/√2.
  const Obstacle tilted = PlaneObstacle{{1.0, 0.0, 0.0}, Vec3(1.0, 1.0, 0.0).normalized()};
  EXPECT_NEAR(signed_distance(tilted, {1.0, 1.0, 7.0}), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(signed_distance(tilted, {0.0, 0.0, -3.0}), -std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(signed_distance(tilted, {0.0, 1.0, 2.0}), 0.0, 1e-15);
}

TEST(Obstacle, VertexInsideASphereGoesToTheClosestOffsetPoint) {
  const SphereObstacle s{{0.0, 0.0, 0.5}, 0.25};
  const double t = 0.002;
  Matrix3X x = positions({{0.1, 0.05, 0.6}, {0.0, 0.0, 0.5 + 0.25 + 0.001}});
  EXPECT_EQ(push_out_of_obstacles({s}, t, free_vertices(2), x), 2);
  for (Eigen::Index i = 0; i < 2; ++i) {
    const Vec3 p = x.row(i).transpose();
    EXPECT_NEAR((p - s.center_m).norm(), s.radius_m + t, tolerance);
  }
  // Along the ray from the centre.
  const Vec3 direction = Vec3(0.1, 0.05, 0.1).normalized();
  EXPECT_NEAR((x.row(0).transpose() - s.center_m).normalized().dot(direction), 1.0, 1e-15);
  EXPECT_NEAR(x(1, 0), 0.0, 0.0);
  EXPECT_NEAR(x(1, 2), 0.5 + 0.25 + t, tolerance);
}

TEST(Obstacle, VertexAtTheSphereCentreGoesOutAlongPlusZ) {
  const SphereObstacle s{{0.3, -0.2, 0.5}, 0.25};
  Matrix3X x = positions({s.center_m});
  EXPECT_EQ(push_out_of_obstacles({s}, 0.002, free_vertices(1), x), 1);
  EXPECT_EQ(x(0, 0), 0.3);
  EXPECT_EQ(x(0, 1), -0.2);
  EXPECT_NEAR(x(0, 2), 0.5 + 0.25 + 0.002, tolerance);
}

TEST(Obstacle, VertexBelowAPlaneMovesAlongTheNormalOnly) {
  const PlaneObstacle tilted{{0.0, 0.0, 0.1}, Vec3(0.0, 0.6, 0.8)};
  const double t = 0.003;
  const Vec3 start(0.4, 0.2, -0.3);
  Matrix3X x = positions({start});
  EXPECT_EQ(push_out_of_obstacles({tilted}, t, free_vertices(1), x), 1);
  const Vec3 moved = x.row(0).transpose() - start;
  EXPECT_NEAR(moved.cross(tilted.normal).norm(), 0.0, 1e-15);  // parallel to the normal
  EXPECT_NEAR(signed_distance(tilted, x.row(0).transpose()), t, tolerance);
}

TEST(Obstacle, VerticesAlreadyOutsideAndPinnedVerticesDoNotMove) {
  const std::vector<Obstacle> obstacles{SphereObstacle{{0.0, 0.0, 0.6}, 0.25},
                                        PlaneObstacle{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}};
  const double t = 0.002;
  const std::vector<Vec3> points = random_points(2000, {-0.5, -0.5, -0.1}, {0.5, 0.5, 1.0}, 7);
  const Matrix3X before = positions(points);
  Eigen::VectorXd inv_mass = free_vertices(before.rows());
  for (Eigen::Index i = 0; i < inv_mass.size(); i += 3) inv_mass[i] = 0.0;  // every third pinned
  // On the offset surfaces exactly, too: at distance t they count as outside.
  Matrix3X x = before;
  int expected_moves = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    bool touching = false;
    for (const Obstacle& o : obstacles) touching |= signed_distance(o, x.row(i).transpose()) < t;
    if (touching && inv_mass[i] > 0.0) ++expected_moves;
  }
  ASSERT_GT(expected_moves, 100);
  EXPECT_EQ(push_out_of_obstacles(obstacles, t, inv_mass, x), expected_moves);

  int outside = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    bool touching = false;
    for (const Obstacle& o : obstacles)
      touching |= signed_distance(o, before.row(i).transpose()) < t;
    if (inv_mass[i] == 0.0 || !touching) {
      ++outside;
      // Bit-exact: the same doubles.
      EXPECT_TRUE(x.row(i) == before.row(i)) << "vertex " << i << " moved";
    }
  }
  EXPECT_GT(outside, 1000);
  Matrix3X free_only = x;
  for (Eigen::Index i = 0; i < x.rows(); i += 3) free_only.row(i) = Vec3(0, 0, 5).transpose();
  EXPECT_TRUE(all_clear(obstacles, t, free_only, tolerance));
}

TEST(Obstacle, VertexOnTheOffsetSurfaceStaysPut) {
  const PlaneObstacle ground{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  Matrix3X x = positions({{0.1, 0.2, 0.002}, {0.1, 0.2, 0.0}});
  const Matrix3X before = x;
  EXPECT_EQ(push_out_of_obstacles({ground}, 0.002, free_vertices(2), x), 1);
  EXPECT_TRUE(x.row(0) == before.row(0));
  // Zero thickness: a vertex on the surface is outside.
  x = before;
  EXPECT_EQ(push_out_of_obstacles({ground}, 0.0, free_vertices(2), x), 0);
  EXPECT_TRUE(x == before);
}

// Random clouds around a sphere floating above the ground, a sphere resting on it (a concave
// wedge around the contact point), two overlapping spheres, and a sharp V between two planes;
// at 1 mm, 1 m and 1 km scale. Both list orders.
class ObstacleScale : public ::testing::TestWithParam<double> {};

TEST_P(ObstacleScale, EveryFreeVertexEndsOutsideEveryObstacle) {
  const double scale = GetParam();
  const double t = 0.002 * scale;
  const double tol = tolerance * std::max(1.0, scale);
  const PlaneObstacle ground{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  const std::vector<std::vector<Obstacle>> cases{
      {SphereObstacle{Vec3(0.0, 0.0, 0.6) * scale, 0.25 * scale}, ground},
      {SphereObstacle{Vec3(0.0, 0.0, 0.25) * scale, 0.25 * scale}, ground},  // resting on it
      {SphereObstacle{Vec3(0.1, 0.0, 0.3) * scale, 0.2 * scale},
       SphereObstacle{Vec3(-0.15, 0.05, 0.3) * scale, 0.15 * scale}},
      // A V-shaped valley with walls 23° apart.
      {PlaneObstacle{{0.0, 0.0, 0.0}, Vec3(std::sin(1.37), 0.0, std::cos(1.37))},
       PlaneObstacle{{0.0, 0.0, 0.0}, Vec3(-std::sin(1.37), 0.0, std::cos(1.37))}},
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    for (bool reversed : {false, true}) {
      std::vector<Obstacle> obstacles = cases[c];
      if (reversed) std::swap(obstacles[0], obstacles[1]);
      const std::vector<Vec3> points =
          random_points(3000, Vec3(-0.5, -0.5, -0.1) * scale, Vec3(0.5, 0.5, 0.9) * scale,
                        static_cast<unsigned>(11 + c));
      Matrix3X x = positions(points);
      const int moved = push_out_of_obstacles(obstacles, t, free_vertices(x.rows()), x);
      EXPECT_GT(moved, 0);
      EXPECT_TRUE(all_clear(obstacles, t, x, tol)) << "case " << c << (reversed ? " reversed" : "");
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, ObstacleScale, ::testing::Values(1e-3, 1.0, 1e3));

TEST(Obstacle, VertexInTheWedgeUnderARestingSphereEndsOutsideBoth) {
  // Sphere of radius r resting on the ground at the origin. Near the contact point the free
  // space is a thin wedge; the offset surfaces meet on the circle of radius ρ at height t.
  const double r = 0.25, t = 0.002;
  const SphereObstacle sphere{{0.0, 0.0, r}, r};
  const PlaneObstacle ground{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  const double rho = std::sqrt((r + t) * (r + t) - (r - t) * (r - t));  // = 2√(r t)
  for (const auto& obstacles :
       {std::vector<Obstacle>{sphere, ground}, std::vector<Obstacle>{ground, sphere}}) {
    Matrix3X x =
        positions({{0.0, 0.0, 0.0}, {0.02, 0.0, 0.001}, {0.0, 0.03, -0.01}, {0.04, 0.0, 0.0015}});
    EXPECT_EQ(push_out_of_obstacles(obstacles, t, free_vertices(4), x), 4);
    EXPECT_TRUE(all_clear(obstacles, t, x, tolerance));
    // The three off the axis go to the nearest point of that circle, keeping their direction.
    EXPECT_NEAR(x.row(1).transpose().dot(Vec3::UnitX()), rho, 1e-12);
    EXPECT_NEAR(x(1, 2), t, tolerance);
    EXPECT_NEAR(x(2, 1), rho, 1e-12);
    EXPECT_NEAR(x(3, 0), rho, 1e-12);
    // The one at the contact point itself ends on the circle too (in a fixed direction).
    EXPECT_NEAR(Vec3(x(0, 0), x(0, 1), 0.0).norm(), rho, 1e-12);
    EXPECT_NEAR(x(0, 2), t, tolerance);
  }
}

TEST(Obstacle, ReturnsTheNumberOfVerticesMoved) {
  const std::vector<Obstacle> obstacles{SphereObstacle{{0.0, 0.0, 0.0}, 1.0}};
  Matrix3X x = positions({{0.0, 0.0, 0.5}, {0.0, 0.0, 2.0}, {0.5, 0.0, 0.0}});
  EXPECT_EQ(push_out_of_obstacles(obstacles, 0.0, free_vertices(3), x), 2);
  EXPECT_EQ(push_out_of_obstacles(obstacles, 0.0, free_vertices(3), x), 0);  // all outside now
  EXPECT_EQ(push_out_of_obstacles({}, 0.1, free_vertices(3), x), 0);
}

TEST(Obstacle, PushesOutOnlyTheListedVertices) {
  const std::vector<Obstacle> obstacles{SphereObstacle{{0.0, 0.0, 0.0}, 1.0}};
  const Matrix3X start = positions({{0.0, 0.0, 0.5}, {0.5, 0.0, 0.0}, {0.0, 0.2, 0.0}});
  Matrix3X x = start;
  EXPECT_EQ(push_out_of_obstacles(obstacles, 0.01, free_vertices(3), std::vector<Index>{0, 2}, x), 2);
  EXPECT_NEAR(x.row(0).norm(), 1.01, tolerance);
  EXPECT_NEAR(x.row(2).norm(), 1.01, tolerance);
  EXPECT_EQ(x.row(1), start.row(1)) << "vertex 1 was not listed";
  Matrix3X all = start;
  push_out_of_obstacles(obstacles, 0.01, free_vertices(3), all);
  EXPECT_EQ(x.row(0), all.row(0)) << "a listed vertex moves as with the whole list";
  try {
    push_out_of_obstacles(obstacles, 0.01, free_vertices(3), std::vector<Index>{3}, x);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
  }
}

// Friction: a vertex that was at x_start (on the ground, at the thickness) and was predicted
// at x, slightly into the ground and sideways.
TEST(ObstacleFriction, KineticFrictionTakesBackFrictionTimesThePushDistance) {
  const std::vector<Obstacle> ground{PlaneObstacle{}};
  const double t = 0.002;
  const Matrix3X start = positions({{0.0, 0.0, t}});
  Matrix3X x = positions({{0.01, 0.0, t - 0.001}});
  EXPECT_EQ(push_out_of_obstacles(ground, t, free_vertices(1), start, 0.5, x), 1);
  EXPECT_NEAR(x(0, 0), 0.01 - 0.5 * 0.001, 1e-15);  // slid 10 mm, held back by μ d = 0.5 mm
  EXPECT_EQ(x(0, 1), 0.0);
  EXPECT_NEAR(x(0, 2), t, 1e-15);
}

TEST(ObstacleFriction, StaticFrictionSticks) {
  const std::vector<Obstacle> ground{PlaneObstacle{}};
  const double t = 0.002;
  const Matrix3X start = positions({{0.3, -0.2, t}});
  Matrix3X x = positions({{0.3002, -0.2001, t - 0.001}});  // slide 0.22 mm < μ d = 0.5 mm
  EXPECT_EQ(push_out_of_obstacles(ground, t, free_vertices(1), start, 0.5, x), 1);
  EXPECT_NEAR(x(0, 0), 0.3, 1e-15);
  EXPECT_NEAR(x(0, 1), -0.2, 1e-15);
  EXPECT_NEAR(x(0, 2), t, 1e-15);
}

TEST(ObstacleFriction, ZeroFrictionIsTheFrictionlessPushOut) {
  const std::vector<Obstacle> obstacles{SphereObstacle{{0.0, 0.0, 0.6}, 0.25},
                                        PlaneObstacle{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}};
  const Matrix3X before = positions(random_points(500, {-0.4, -0.4, -0.1}, {0.4, 0.4, 0.9}, 3));
  const Matrix3X start = before + Matrix3X::Constant(before.rows(), 3, 0.01);
  Matrix3X frictionless = before, zero = before;
  push_out_of_obstacles(obstacles, 0.002, free_vertices(before.rows()), frictionless);
  push_out_of_obstacles(obstacles, 0.002, free_vertices(before.rows()), start, 0.0, zero);
  EXPECT_TRUE(zero == frictionless);
}

TEST(ObstacleFriction, KeepsEveryVertexOutsideAndLeavesTheOthersAlone) {
  const std::vector<Obstacle> obstacles{SphereObstacle{{0.0, 0.0, 0.25}, 0.25},
                                        PlaneObstacle{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}};
  const double t = 0.002;
  const std::vector<Vec3> points = random_points(3000, {-0.5, -0.5, -0.1}, {0.5, 0.5, 0.6}, 5);
  const Matrix3X before = positions(points);
  // Each vertex came from 1 cm away in a random direction.
  const Matrix3X start = before + 0.01 * positions(random_points(3000, {-1, -1, -1}, {1, 1, 1}, 6));
  Eigen::VectorXd inv_mass = free_vertices(before.rows());
  for (Eigen::Index i = 0; i < inv_mass.size(); i += 4) inv_mass[i] = 0.0;
  Matrix3X x = before;
  EXPECT_GT(push_out_of_obstacles(obstacles, t, inv_mass, start, 0.8, x), 100);
  Matrix3X free_only = x;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    bool touching = false;
    for (const Obstacle& o : obstacles)
      touching |= signed_distance(o, before.row(i).transpose()) < t;
    if (inv_mass[i] == 0.0 || !touching) {
      EXPECT_TRUE(x.row(i) == before.row(i)) << i;
    }
    if (inv_mass[i] == 0.0) free_only.row(i) = Vec3(0, 0, 5).transpose();
  }
  EXPECT_TRUE(all_clear(obstacles, t, free_only, tolerance));
}

TEST(Obstacle, BadInputThrows) {
  Matrix3X x = positions({{0.0, 0.0, 0.0}});
  const std::vector<Obstacle> ground{PlaneObstacle{}};
  EXPECT_THROW(push_out_of_obstacles(ground, 0.002, Eigen::VectorXd::Ones(2), x),
               std::invalid_argument);
  EXPECT_THROW(push_out_of_obstacles(ground, -0.001, free_vertices(1), x), std::invalid_argument);
  EXPECT_THROW(push_out_of_obstacles(ground, NAN, free_vertices(1), x), std::invalid_argument);
  EXPECT_THROW(push_out_of_obstacles(ground, 0.002, free_vertices(1), x, -0.1, x),
               std::invalid_argument);
  EXPECT_THROW(push_out_of_obstacles(ground, 0.002, free_vertices(1), positions({}), 0.5, x),
               std::invalid_argument);
  EXPECT_THROW(check_obstacles({PlaneObstacle{{0, 0, 0}, {0, 0, 2}}}), std::invalid_argument);
  EXPECT_THROW(check_obstacles({SphereObstacle{{0, 0, 0}, 0.0}}), std::invalid_argument);
  EXPECT_THROW(check_obstacles({SphereObstacle{{0, 0, NAN}, 1.0}}), std::invalid_argument);
  try {
    check_obstacles({PlaneObstacle{}, SphereObstacle{{0, 0, 0}, -1.0}});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("obstacle 1: sphere radius", 0), 0u) << e.what();
  }
  EXPECT_NO_THROW(check_obstacles({PlaneObstacle{{0, 0, 0}, {0, 0, 1.0000001}}}));
}

}  // namespace
}  // namespace weft::sim
