// Continuous collision detection and rigid impact zones: the kernels against cases
// with a known time of impact, and the zones' invariants.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <random>

#include "sim/collision/continuous_collision.h"
#include "sim/collision/impact_zones.h"
#include "sim/collision/proximity.h"
#include "sim/collision/self_intersection.h"
#include "tests/sim/rolled_sheet.h"

namespace weft::sim {
namespace {

constexpr double kEta = 1e-5;  // m

// A triangle in the plane z = 0 and a vertex falling through it: f(t) has its root where
// z(t) = 0, here t = 1/4.
TEST(ContinuousCollision, VertexThroughTriangleAtItsCrossingTime) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Vec3 p0(0.2, 0.2, 1.0), p1(0.2, 0.2, -3.0);
  const auto t = vertex_triangle_impact(p0, a, b, c, p1, a, b, c, kEta);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.25, 1e-9);
  // Reversed in time: the same crossing at 3/4.
  const auto back = vertex_triangle_impact(p1, a, b, c, p0, a, b, c, kEta);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(*back, 0.75, 1e-9);
}

// The triangle moves up through a vertex at rest while tilting: the plane passes the vertex
// where (1 − t)·(−1) + t·1 = 0 at the vertex's (x, y), here t = 1/2.
TEST(ContinuousCollision, MovingTriangleThroughVertexAtRest) {
  const Vec3 p(0.25, 0.25, 0.0);
  const Vec3 a0(0, 0, -1), b0(1, 0, -1), c0(0, 1, -1);
  const Vec3 a1(0, 0, 1), b1(1, 0, 1), c1(0, 1, 1);
  const auto t = vertex_triangle_impact(p, a0, b0, c0, p, a1, b1, c1, kEta);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, 1e-9);
  // Translated far away and scaled down the time is the same.
  const Vec3 shift(1e3, -2e3, 5e2);
  const auto moved = vertex_triangle_impact(p * 1e-3 + shift, a0 * 1e-3 + shift, b0 * 1e-3 + shift,
                                            c0 * 1e-3 + shift, p * 1e-3 + shift, a1 * 1e-3 + shift,
                                            b1 * 1e-3 + shift, c1 * 1e-3 + shift, 1e-3 * kEta);
  ASSERT_TRUE(moved.has_value());
  EXPECT_NEAR(*moved, 0.5, 1e-6);
}

// A vertex passing the triangle's edge outside it: a miss by 2 eta is no impact, by eta / 2
// it is (the thickness counts).
TEST(ContinuousCollision, NearMissesOutsideTheTriangleCountOnlyWithinEta) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Vec3 p0(0.5, -2 * kEta, 1.0), p1(0.5, -2 * kEta, -1.0);
  EXPECT_FALSE(vertex_triangle_impact(p0, a, b, c, p1, a, b, c, kEta).has_value());
  const Vec3 q0(0.5, -0.5 * kEta, 1.0), q1(0.5, -0.5 * kEta, -1.0);
  const auto t = vertex_triangle_impact(q0, a, b, c, q1, a, b, c, kEta);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, 1e-9);
  // Stopping 2 eta short of the plane is no impact; ending eta / 2 above it is one, at t = 1.
  EXPECT_FALSE(vertex_triangle_impact(Vec3(0.2, 0.2, 1.0), a, b, c, Vec3(0.2, 0.2, 2 * kEta), a,
                                      b, c, kEta)
                   .has_value());
  const auto end = vertex_triangle_impact(Vec3(0.2, 0.2, 1.0), a, b, c,
                                          Vec3(0.2, 0.2, 0.5 * kEta), a, b, c, kEta);
  ASSERT_TRUE(end.has_value());
  EXPECT_DOUBLE_EQ(*end, 1.0);
  // Moving parallel to the plane, 2 eta above it: never coplanar, no impact.
  EXPECT_FALSE(vertex_triangle_impact(Vec3(-1, 0.2, 2 * kEta), a, b, c, Vec3(2, 0.2, 2 * kEta), a,
                                      b, c, kEta)
                   .has_value());
}

// Two crossed edges, one falling through the other: impact when their heights meet, t = 1/2.
TEST(ContinuousCollision, EdgeThroughEdgeAndAVertexRidingTheTrianglesPlane) {
  const Vec3 r(0, -1, 0), s(0, 1, 0);
  const auto t = edge_edge_impact(Vec3(-1, 0, 1), Vec3(1, 0, 1), r, s, Vec3(-1, 0, -1),
                                  Vec3(1, 0, -1), r, s, kEta);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, 1e-9);
  // Shifted sideways past r's end by 2 eta: a near miss.
  const Vec3 r2(0, 2 * kEta, 0), s2(0, 1, 0);
  EXPECT_FALSE(edge_edge_impact(Vec3(-1, 0, 1), Vec3(1, 0, 1), r2, s2, Vec3(-1, 0, -1),
                                Vec3(1, 0, -1), r2, s2, kEta)
                   .has_value());
  // A vertex riding the triangle's plane as it turns about the x axis (z = y (1 − 2t) and the
  // vertex at y = 1/2, z = 1/2 − t), inside the triangle throughout: f ≡ 0, and the coplanar
  // search reports the first time after the start.
  const Vec3 a(0, 0, 0), b(1, 0, 0);
  const Vec3 c0(0, 1, 1), c1(0, 1, -1);
  const Vec3 p0(0.2, 0.5, 0.5), p1(0.2, 0.5, -0.5);
  const auto ride = vertex_triangle_impact(p0, a, b, c0, p1, a, b, c1, kEta);
  ASSERT_TRUE(ride.has_value());
  EXPECT_LT(*ride, 0.01);
}

// Parallel edges in one plane sliding through each other: f ≡ 0, found by the coplanar search
// at the time their gap closes; parallel edges in parallel planes 2 eta apart never meet.
TEST(ContinuousCollision, ParallelEdges) {
  // pq on the x axis at y = 1 → y = −1; rs on the x axis at y = 0: the gap closes at t = 1/2.
  const Vec3 r(0, 0, 0), s(1, 0, 0);
  const auto t = edge_edge_impact(Vec3(0.5, 1, 0), Vec3(1.5, 1, 0), r, s, Vec3(0.5, -1, 0),
                                  Vec3(1.5, -1, 0), r, s, kEta);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, kEta);
  EXPECT_LE(*t, 0.5);
  EXPECT_FALSE(edge_edge_impact(Vec3(0.5, 1, 2 * kEta), Vec3(1.5, 1, 2 * kEta), r, s,
                                Vec3(0.5, -1, 2 * kEta), Vec3(1.5, -1, 2 * kEta), r, s, kEta)
                   .has_value());
}

// The coefficients against the determinant at sample times.
TEST(ContinuousCollision, CubicMatchesTheDeterminant) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto rv = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 u0 = rv(), du = rv(), v0 = rv(), dv = rv(), w0 = rv(), dw = rv();
    const CoplanarityCubic f = coplanarity_cubic(u0, du, v0, dv, w0, dw);
    for (const double t : {0.0, 0.3, 0.7, 1.0})
      EXPECT_NEAR(f(t), (u0 + t * du).cross(v0 + t * dv).dot(w0 + t * dw), 1e-12);
  }
}

// Conservative against dense sampling, on random small motions of pairs that start near each
// other (the cases the early verdict "apart all step" decides): a pair that passes through
// coplanarity (f changes sign between two samples) within eta / 2, or ends within eta / 2, is
// an impact, and every reported impact is within eta at its time.
TEST(ContinuousCollision, SmallMotionsAgreeWithDenseSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double eta = 1e-3;
  const auto rv = [&](double scale) -> Vec3 { return Vec3(u(rng), u(rng), u(rng)) * scale; };
  const auto lerp = [](const Vec3& a, const Vec3& b, double t) -> Vec3 { return a + t * (b - a); };
  int impacts = 0, misses = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    // Features of ~1 cm, their centres 0.2–0.8 cm apart (from crossing to mm apart), each
    // vertex moving up to 3 mm per coordinate.
    const bool vt = trial % 2 == 0;
    const Vec3 offset = rv(1.0).normalized() * (0.005 + 0.003 * u(rng));
    std::array<Vec3, 4> x0{}, x1{};
    for (int k = 0; k < 4; ++k) {
      x0[k] = rv(0.005) + (k >= (vt ? 1 : 2) ? offset : Vec3::Zero());
      x1[k] = x0[k] + rv(0.003);
    }
    const auto distance = [&](double t) {
      std::array<Vec3, 4> x{};
      for (int k = 0; k < 4; ++k) x[k] = lerp(x0[k], x1[k], t);
      if (vt) {
        const Vec3 w = closest_point_on_triangle_weights(x[0], x[1], x[2], x[3]);
        return (x[0] - (w[0] * x[1] + w[1] * x[2] + w[2] * x[3])).norm();
      }
      const auto st = closest_segment_parameters(x[0], x[1], x[2], x[3]);
      return ((x[0] + st[0] * (x[1] - x[0])) - (x[2] + st[1] * (x[3] - x[2]))).norm();
    };
    const auto hit = vt ? vertex_triangle_impact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1],
                                                 x1[2], x1[3], eta)
                        : edge_edge_impact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2],
                                           x1[3], eta);
    const auto coplanarity = [&](double t) {
      std::array<Vec3, 4> x{};
      for (int k = 0; k < 4; ++k) x[k] = lerp(x0[k], x1[k], t);
      return (x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]);
    };
    constexpr int samples = 2000;
    double closest = distance(0.0), f_before = coplanarity(0.0), d_before = closest;
    bool must_hit = false;
    for (int s = 1; s <= samples; ++s) {
      const double t = double(s) / samples, f = coplanarity(t), d = distance(t);
      must_hit |= (f_before < 0.0) != (f < 0.0) && std::min(d_before, d) < 0.5 * eta;
      closest = std::min(closest, d);
      f_before = f;
      d_before = d;
    }
    must_hit |= d_before < 0.5 * eta;
    if (must_hit) {
      EXPECT_TRUE(hit.has_value()) << "trial " << trial;
    }
    if (hit) {
      EXPECT_LT(distance(*hit), eta * (1.0 + 1e-6)) << "trial " << trial;
    }
    impacts += hit.has_value();
    misses += closest > eta;
  }
  // Both verdicts occur often.
  EXPECT_GT(impacts, 200);
  EXPECT_GT(misses, 400);
  std::cout << impacts << " impacts, " << misses << " pairs apart by more than eta all step\n";
}

// A zone's rigid motion keeps every distance between its vertices, the centre of mass's
// displacement (linear momentum), and — to first order in the angle — the angular momentum of
// the proposed displacements.
TEST(ImpactZones, RigidMotionKeepsDistancesAndMomentum) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 12;
  Matrix3X x0(n, 3), proposed(n, 3);
  Eigen::VectorXd mass(n);
  for (int i = 0; i < n; ++i) {
    x0.row(i) = Vec3(u(rng), u(rng), u(rng)).transpose() * 0.01;
    mass[i] = 1.0 + 0.5 * u(rng);
  }
  // A small rotation about an axis, a translation, and noise that a rigid motion cannot follow.
  const Eigen::AngleAxisd turn(1e-3, Vec3(1, 2, 3).normalized());
  const Vec3 shift(2e-3, -1e-3, 5e-4);
  for (int i = 0; i < n; ++i)
    proposed.row(i) =
        (turn * vertex(x0, i) + shift + 1e-4 * Vec3(u(rng), u(rng), u(rng))).transpose();
  std::vector<Index> zone;
  for (Index i = 0; i < n; ++i) zone.push_back(i);
  Matrix3X x = proposed;
  apply_rigid_zone_motion(zone, x0, proposed, mass, x);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      EXPECT_NEAR((vertex(x, i) - vertex(x, j)).norm(), (vertex(x0, i) - vertex(x0, j)).norm(),
                  1e-15);
  Vec3 p_proposed = Vec3::Zero(), p_rigid = Vec3::Zero(), c0 = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    p_proposed += mass[i] * (vertex(proposed, i) - vertex(x0, i));
    p_rigid += mass[i] * (vertex(x, i) - vertex(x0, i));
    c0 += mass[i] * vertex(x0, i);
  }
  c0 /= mass.sum();
  EXPECT_LT((p_rigid - p_proposed).norm(), 1e-15);
  Vec3 l_proposed = Vec3::Zero(), l_rigid = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec3 r = vertex(x0, i) - c0;
    l_proposed += mass[i] * r.cross(vertex(proposed, i) - vertex(x0, i));
    l_rigid += mass[i] * r.cross(vertex(x, i) - vertex(x0, i));
  }
  // The rotation's chord differs from its tangent by O(angle²).
  EXPECT_LT((l_rigid - l_proposed).norm(), 1e-3 * l_proposed.norm());
}

// Two 9×9 sheets 1 mm apart, the top one pushed 5 mm down through the bottom one within the
// step: the zones leave no crossing, every zone moves rigidly from its start, and a free sheet
// not involved keeps its proposed motion.
TEST(ImpactZones, SheetPushedThroughAnotherEndsWithoutCrossing) {
  const int m = 9;
  const double spacing = 0.01;
  std::vector<std::array<Index, 3>> triangles;
  Matrix3X x0(3 * m * m, 3);
  for (int layer = 0; layer < 3; ++layer) {
    const Index base = layer * m * m;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        x0.row(base + j * m + i) =
            Vec3((i + (layer == 1 ? 0.37 : 0.0)) * spacing + (layer == 2 ? 1.0 : 0.0),
                 (j + (layer == 1 ? 0.29 : 0.0)) * spacing, layer == 1 ? 1e-3 : 0.0)
                .transpose();
    for (int j = 0; j + 1 < m; ++j)
      for (int i = 0; i + 1 < m; ++i) {
        const Index v = base + j * m + i;
        triangles.push_back({v, v + 1, v + m + 1});
        triangles.push_back({v, v + m + 1, v + m});
      }
  }
  Matrix3X x = x0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-1e-4, 1e-4);
  for (int k = m * m; k < 2 * m * m; ++k)  // the top sheet tilted through the bottom one
    x(k, 2) -= 6e-3 * ((k - m * m) % m) / (m - 1.0) + noise(rng);
  for (int k = 2 * m * m; k < 3 * m * m; ++k) x(k, 1) += 2e-3;  // the far sheet slides
  const Matrix3X proposed = x;
  const auto edges = unique_edges(triangles);
  ASSERT_GT(count_edge_triangle_crossings(x, triangles, edges), 0);
  Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(3 * m * m);
  ImpactZones zones(triangles, 1e-4);
  const ImpactZoneCounts counts = zones.resolve(x0, inv_mass, x);
  EXPECT_TRUE(counts.resolved);
  EXPECT_GT(counts.collisions, 0);
  EXPECT_EQ(count_edge_triangle_crossings(x, triangles, edges), 0);
  for (int k = 2 * m * m; k < 3 * m * m; ++k) EXPECT_EQ(x.row(k), proposed.row(k));
  // A second pass over the result finds nothing more.
  Matrix3X again = x;
  const ImpactZoneCounts second = zones.resolve(x0, inv_mass, again);
  EXPECT_EQ(second.collisions, 0);
  EXPECT_EQ(again, x);
  // With one zone, every edge inside it keeps its start length.
  const auto& in_zone = zones.zone_vertices();
  if (counts.zones == 1)
    for (const auto& e : edges) {
      if (std::binary_search(in_zone.begin(), in_zone.end(), e[0]) &&
          std::binary_search(in_zone.begin(), in_zone.end(), e[1])) {
        EXPECT_NEAR((vertex(x, e[0]) - vertex(x, e[1])).norm(),
                    (vertex(x0, e[0]) - vertex(x0, e[1])).norm(), 1e-12);
      }
    }
  std::cout << "sheets: " << counts.passes << " passes, " << counts.collisions << " collisions, "
            << counts.zones << " zones of " << counts.zone_vertices << " vertices\n";
}

// Resolves the step from x to `proposed` with two candidate searches, which must give the same
// bits and collisions; moves x to the result and returns the collisions.
long resolve_alike(ImpactZones& first, ImpactZones& second, const Eigen::VectorXd& inv_mass,
                   const Matrix3X& proposed, Matrix3X& x, int step) {
  Matrix3X a_x = proposed, b_x = proposed;
  const ImpactZoneCounts a = first.resolve(x, inv_mass, a_x);
  const ImpactZoneCounts b = second.resolve(x, inv_mass, b_x);
  EXPECT_EQ(a_x, b_x) << "step " << step;
  EXPECT_EQ(a.collisions, b.collisions) << "step " << step;
  x = a_x;
  return a.collisions;
}

// The cached candidate list only saves time: a sheet folded over itself and moved on for a
// few steps by random motions, large and small, gives the same bits with one ImpactZones kept
// across the steps (its list reused while it holds) as with a new one at every step.
TEST(ImpactZones, CachedCandidatesGiveTheBitsOfAFreshSearch) {
  const int m = 12;
  const double spacing = 0.01;
  std::vector<std::array<Index, 3>> triangles;
  Matrix3X x(2 * m * m, 3);
  for (int layer = 0; layer < 2; ++layer)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const Index v = layer * m * m + j * m + i;
        x.row(v) = Vec3((i + 0.3 * layer) * spacing, (j + 0.2 * layer) * spacing, 2e-3 * layer)
                       .transpose();
        if (i + 1 < m && j + 1 < m) {
          triangles.push_back({v, v + 1, v + m + 1});
          triangles.push_back({v, v + m + 1, v + m});
        }
      }
  const Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(2 * m * m);
  ImpactZones kept(triangles, 1e-4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  long collisions = 0;
  for (int step = 0; step < 12; ++step) {
    const double size = step % 4 == 3 ? 4e-3 : 3e-4;  // now and then beyond the reach
    Matrix3X proposed = x;
    for (Index v = 0; v < proposed.rows(); ++v)
      proposed.row(v) += (size * Vec3(u(rng), u(rng), u(rng)) + Vec3(1e-3, 0, -2e-3 * (v >= m * m)))
                             .transpose();
    ImpactZones fresh(triangles, 1e-4);
    collisions += resolve_alike(kept, fresh, inv_mass, proposed, x, step);
  }
  EXPECT_GT(collisions, 0);                 // the layers met
  EXPECT_LT(kept.candidate_rebuilds(), 12);  // and the list was reused
}

// On a grid the pairs come from patches whose normal cones over the step rule out the flat
// ones. That only saves time: a sheet rolled into a spiral, its layers 4 mm apart, squeezed and
// shaken by random motions, large and small, for a few steps gives the same bits as the search
// over every pair (the cached list, as on a mesh without a grid). A flat sheet shaken a little
// has no pair to test on patches, and thousands of neighbours to test without them.
TEST(ImpactZones, PatchCullingGivesTheBitsOfTheFullSearch) {
  const ClothMesh mesh = sheet(65);
  const auto triangles = mesh.triangles();
  const Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(mesh.vertex_count());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  {
    ImpactZones on_patches(mesh, 1e-4), on_all(triangles, 1e-4);
    Matrix3X shaken = mesh.rest_positions, with_all = shaken;
    for (Index v = 0; v < shaken.rows(); ++v) shaken.row(v) += 2e-4 * Vec3(u(rng), u(rng), u(rng)).transpose();
    with_all = shaken;
    on_patches.resolve(mesh.rest_positions, inv_mass, shaken);
    on_all.resolve(mesh.rest_positions, inv_mass, with_all);
    EXPECT_EQ(shaken, with_all);
    EXPECT_EQ(on_patches.tested_pairs(), 0);
    EXPECT_GT(on_all.tested_pairs(), 10000);
  }
  ImpactZones on_patches(mesh, 1e-4), on_all(triangles, 1e-4);
  Matrix3X x = rolled(mesh, 0.1, 0.004);
  long collisions = 0;
  for (int step = 0; step < 10; ++step) {
    const double size = step % 3 == 2 ? 3e-3 : 2e-4;
    Matrix3X proposed = x;
    for (Index v = 0; v < proposed.rows(); ++v) {
      const Vec3 inward = -Vec3(x(v, 0), 0.0, x(v, 2) - 0.5).normalized();  // towards the roll's axis
      proposed.row(v) += (size * Vec3(u(rng), u(rng), u(rng)) + 1.5e-3 * inward).transpose();
    }
    collisions += resolve_alike(on_patches, on_all, inv_mass, proposed, x, step);
  }
  EXPECT_GT(collisions, 0);  // the layers met
  EXPECT_LT(on_patches.tested_pairs(), on_all.tested_pairs());
  std::cout << "rolled sheet, pairs tested: " << on_patches.tested_pairs() << " on patches, "
            << on_all.tested_pairs() << " in all; " << collisions << " collisions\n";
}

}  // namespace
}  // namespace weft::sim
