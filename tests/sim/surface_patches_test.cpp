// The self-collision broad phase on patches (sim/collision/surface_patches.h): patches
// partition the triangles and own each vertex and edge once; a flat sheet needs no pair; and,
// on a sheet rolled into a spiral whose layers lie within reach of each other, every feature
// pair within reach that is not a rest neighbour lies in a returned patch pair, while the
// normal cones drop most of the patch pairs of the gently curved layers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "base/constants.h"
#include "sim/collision/proximity.h"
#include "sim/collision/self_collision.h"
#include "sim/collision/self_intersection.h"
#include "sim/collision/surface_patches.h"
#include "sim/grid.h"
#include "tests/sim/rolled_sheet.h"

namespace weft::sim {
namespace {

TEST(SurfacePatches, PartitionTrianglesAndOwnEachVertexAndEdgeOnce) {
  for (const SpecimenShape shape : {SpecimenShape::rectangle, SpecimenShape::disc}) {
    const ClothMesh mesh = sheet(17, shape);
    const auto triangles = mesh.triangles();
    const auto edges = unique_edges(triangles);
    const SurfacePatches patches(mesh, triangles, edges, 2);
    std::vector<int> triangle_seen(triangles.size()), vertex_seen(mesh.vertex_count()),
        edge_seen(edges.size());
    for (const SurfacePatch& p : patches.patches()) {
      EXPECT_LE(p.triangles.size(), 8u);
      for (const Index t : p.triangles) ++triangle_seen[static_cast<std::size_t>(t)];
      for (const Index v : p.owned_vertices) ++vertex_seen[static_cast<std::size_t>(v)];
      for (const Index e : p.owned_edges) ++edge_seen[static_cast<std::size_t>(e)];
    }
    for (const int c : triangle_seen) EXPECT_EQ(c, 1);
    for (Index v = 0; v < mesh.vertex_count(); ++v)
      EXPECT_EQ(vertex_seen[static_cast<std::size_t>(v)], mesh.is_used(v) ? 1 : 0) << "vertex " << v;
    for (const int c : edge_seen) EXPECT_EQ(c, 1);
  }
}

TEST(SurfacePatches, AFlatSheetNeedsNoPairButEveryNeighbourPairWithoutCulling) {
  const ClothMesh mesh = sheet(33);
  const auto triangles = mesh.triangles();
  const auto edges = unique_edges(triangles);
  SurfacePatches patches(mesh, triangles, edges, 2);
  // Tilted and moved: cones do not depend on the sheet's placement.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Matrix3X x = (mesh.rest_positions * turn.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);
  patches.refit(x);
  std::vector<std::array<Index, 2>> pairs;
  patches.near_pairs(0.01, ConeCulling{0.05}, pairs);  // flat angle 60°: acos(0.01 / 0.05) capped
  EXPECT_TRUE(pairs.empty());
  patches.near_pairs(0.01, ConeCulling{}, pairs);
  // 16 × 16 patches: each with itself, 2·16·15 side neighbours and 2·15·15 diagonal ones.
  EXPECT_EQ(pairs.size(), 256u + 480u + 450u);
  for (const SurfacePatch& p : patches.patches()) {
    EXPECT_LT(p.cone_angle_rad, 1e-6);  // acos rounding
    EXPECT_NEAR(p.least_stretch, 1.0, 1e-9) << "a rigid motion does not stretch";
  }
}

// The cones' bound needs the cloth's least stretch: squeezed to 60 % along the warp, the
// flat sheet's points come nearer than their rest distances, and a culling that rules out
// every pair at rest length (flat angle 33.6°: reach / exclusion = 0.833) rules out none.
TEST(SurfacePatches, ASqueezedSheetIsNotCulledAsIfAtRest) {
  const ClothMesh mesh = sheet(33);
  const auto triangles = mesh.triangles();
  SurfacePatches patches(mesh, triangles, unique_edges(triangles), 2);
  const ConeCulling culling{0.012};
  std::vector<std::array<Index, 2>> pairs;
  patches.near_pairs(0.01, culling, pairs);
  EXPECT_TRUE(pairs.empty());
  Matrix3X squeezed = mesh.rest_positions;
  squeezed.col(0) *= 0.6;
  patches.refit(squeezed);
  for (const SurfacePatch& p : patches.patches()) EXPECT_NEAR(p.least_stretch, 0.6, 1e-9);
  EXPECT_EQ(culling.flat_angle_rad(0.01, 0.6), 0.0);
  patches.near_pairs(0.01, culling, pairs);
  std::vector<std::array<Index, 2>> all;
  patches.near_pairs(0.01, ConeCulling{}, all);
  EXPECT_EQ(pairs, all);
}

TEST(SurfacePatches, ARolledSheetKeepsEveryPairWithinReach) {
  const ClothMesh mesh = sheet(65);
  SelfCollisionSettings settings;
  settings.enabled = true;
  settings.thickness_m = 3e-3;
  const SelfCollision self(mesh, settings);
  ASSERT_GT(self.cone_culling().flat_angle_rad(self.margin_m() + self.thickness_m(), 0.9), 0.0);
  const double reach_m =
      std::max(self.thickness_m(), 2.0 * self.marble_radius_m()) + self.margin_m();
  const Matrix3X x = rolled(mesh, 0.12, 0.006);  // 1.3 turns, layers 6 mm apart

  const auto triangles = mesh.triangles();
  const auto edges = unique_edges(triangles);
  SurfacePatches patches(mesh, triangles, edges, SelfCollision::cells_per_patch_side);
  patches.refit(x);
  std::vector<std::array<Index, 2>> culled, all;
  patches.near_pairs(reach_m, self.cone_culling(), culled);
  patches.near_pairs(reach_m, ConeCulling{}, all);
  const std::set<std::array<Index, 2>> kept(culled.begin(), culled.end());
  EXPECT_LT(culled.size(), all.size() / 2) << "the cones should drop the gently curved layers' pairs";

  std::vector<Index> vertex_owner(mesh.vertex_count(), -1), edge_owner(edges.size(), -1),
      triangle_patch(triangles.size(), -1);
  for (Index p = 0; p < static_cast<Index>(patches.patches().size()); ++p) {
    for (const Index v : patches[p].owned_vertices) vertex_owner[static_cast<std::size_t>(v)] = p;
    for (const Index e : patches[p].owned_edges) edge_owner[static_cast<std::size_t>(e)] = p;
    for (const Index t : patches[p].triangles) triangle_patch[static_cast<std::size_t>(t)] = p;
  }
  const auto covered = [&](Index p, Index q) { return kept.count({std::min(p, q), std::max(p, q)}) > 0; };
  const auto row = [&](const Matrix3X& m, Index v) -> Vec3 { return m.row(v).transpose(); };
  const double exclusion_m = self.exclusion_radius_m();
  long near_pairs = 0;
  for (Index v = 0; v < mesh.vertex_count(); ++v)
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const auto& tri = triangles[t];
      if (v == tri[0] || v == tri[1] || v == tri[2]) continue;
      if (std::abs(x(v, 1) - x(tri[0], 1)) > 0.05) continue;  // far apart across the roll
      const auto distance = [&](const Matrix3X& m) {
        const Vec3 w = closest_point_on_triangle_weights(row(m, v), row(m, tri[0]), row(m, tri[1]), row(m, tri[2]));
        return (row(m, v) - (w[0] * row(m, tri[0]) + w[1] * row(m, tri[1]) + w[2] * row(m, tri[2]))).norm();
      };
      if (distance(x) >= reach_m || distance(mesh.rest_positions) < exclusion_m) continue;
      ++near_pairs;
      ASSERT_TRUE(covered(vertex_owner[static_cast<std::size_t>(v)], triangle_patch[t]))
          << "vertex " << v << " and triangle " << t;
    }
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const auto& e = edges[i];
      const auto& f = edges[j];
      if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) continue;
      if (std::abs(x(e[0], 1) - x(f[0], 1)) > 0.05) continue;  // far apart across the roll
      const auto distance = [&](const Matrix3X& m) {
        const auto [s, u] = closest_segment_parameters(row(m, e[0]), row(m, e[1]), row(m, f[0]), row(m, f[1]));
        return ((row(m, e[0]) + s * (row(m, e[1]) - row(m, e[0]))) - (row(m, f[0]) + u * (row(m, f[1]) - row(m, f[0])))).norm();
      };
      if (distance(x) >= reach_m || distance(mesh.rest_positions) < exclusion_m) continue;
      ++near_pairs;
      ASSERT_TRUE(covered(edge_owner[i], edge_owner[j])) << "edges " << i << " and " << j;
    }
  EXPECT_GT(near_pairs, 1000) << "the layers should be within reach of each other";
}

// Over a step, refit_swept's box, cone and least stretch hold every triangle of a patch at
// every time along the straight paths: the rolled sheet moved to a squeezed, shaken one,
// sampled at 201 times. And a flat sheet moved rigidly keeps a zero cone and unit stretch.
TEST(SurfacePatches, SweptRefitBoundsEveryTimeAlongThePaths) {
  const ClothMesh mesh = sheet(17);
  const auto triangles = mesh.triangles();
  const auto edges = unique_edges(triangles);
  SurfacePatches patches(mesh, triangles, edges, 2);
  const Matrix3X x0 = rolled(mesh, 0.08, 0.005);
  Matrix3X x1 = 0.9 * x0;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3e-3, 3e-3);
  for (Index v = 0; v < x1.rows(); ++v) x1.row(v) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  patches.refit_swept(x0, x1);
  SurfacePatches at_time(mesh, triangles, edges, 2);
  for (int k = 0; k <= 200; ++k) {
    const double t = k / 200.0;
    const Matrix3X x = (1.0 - t) * x0 + t * x1;
    at_time.refit(x);
    for (std::size_t p = 0; p < patches.patches().size(); ++p) {
      const SurfacePatch& swept = patches.patches()[p];
      const SurfacePatch& now = at_time.patches()[p];
      EXPECT_TRUE((swept.box.lo.array() <= now.box.lo.array()).all() &&
                  (now.box.hi.array() <= swept.box.hi.array()).all()) << "patch " << p << " at t " << t;
      EXPECT_LE(swept.least_stretch, now.least_stretch + 1e-12) << "patch " << p << " at t " << t;
      const Vec3 axis = swept.normal_sum.normalized();
      for (const Index tri : now.triangles) {
        const auto& c = triangles[static_cast<std::size_t>(tri)];
        const Vec3 n = (vertex(x, c[1]) - vertex(x, c[0])).cross(vertex(x, c[2]) - vertex(x, c[0]));
        EXPECT_LE(std::acos(std::clamp(axis.dot(n.normalized()), -1.0, 1.0)), swept.cone_angle_rad + 1e-9)
            << "triangle " << tri << " at t " << t;
      }
    }
  }
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3, Vec3(0, 1, 0)).toRotationMatrix();
  const Matrix3X moved = (mesh.rest_positions * turn.transpose()).rowwise() + Eigen::RowVector3d(0, 0, -0.1);
  patches.refit_swept(mesh.rest_positions, moved);
  for (const SurfacePatch& p : patches.patches()) {
    EXPECT_LT(p.cone_angle_rad, 0.3 + 1e-9);  // a turn of 0.3 rad sweeps the normals that far
    // The bound (σ₀ + σ₁ − ‖ΔF‖)/2 with σ = 1 and the warp's column turned: ‖ΔF‖ = 2 sin 0.15.
    EXPECT_NEAR(p.least_stretch, 1.0 - std::sin(0.15), 1e-9);
  }
}

}  // namespace
}  // namespace weft::sim
