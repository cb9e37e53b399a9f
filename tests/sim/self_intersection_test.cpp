// Self-intersection check: the segment–triangle kernel on hand-made cases, zero
// crossings on flat and smooth sheets, the exact count for two strips that pass through each
// other, hashed = brute force on random crumpled sheets, invariance under scale (×1e-3, ×1e3)
// and translation, and the spatial hash returning exactly the overlapping boxes in any box order.

#include "sim/collision/self_intersection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "sim/collision/spatial_hash.h"
#include "sim/grid.h"

namespace weft::sim {
namespace {

using Triangles = std::vector<std::array<Index, 3>>;

struct Mesh {
  Matrix3X x;
  Triangles triangles;
};

Mesh grid_mesh(const GridSpec& spec) {
  const ClothMesh cloth = make_grid(spec);
  return {cloth.rest_positions, cloth.triangles()};
}

// Both meshes as one (b's indices shifted after a's vertices).
Mesh join(const Mesh& a, const Mesh& b) {
  Mesh m;
  m.x.resize(a.x.rows() + b.x.rows(), 3);
  m.x << a.x, b.x;
  m.triangles = a.triangles;
  const Index offset = static_cast<Index>(a.x.rows());
  for (const auto& t : b.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return m;
}

std::vector<EdgeTriangleCrossing> crossings(const Mesh& m) {
  return find_edge_triangle_crossings(m.x, m.triangles, unique_edges(m.triangles));
}

// Sheet A: 7×7 vertices at integer (x, y) in [0, 6]², z = 0. Strip B: vertical, in the plane
// y = 2.3, x ∈ [0.6, 4.6] (5 columns at x = 0.6 + k), z ∈ {−1, +1} (one row of quads whose
// diagonals run from (x_k, −1) to (x_k+1, +1)). No crossing point lies on an edge of either.
Mesh crossing_strips() {
  GridSpec a;
  a.size_u_m = a.size_v_m = 6.0;
  a.nu = a.nv = 7;
  a.origin = Vec3(0.0, 0.0, 0.0);
  GridSpec b;
  b.size_u_m = 4.0;
  b.size_v_m = 2.0;
  b.nu = 5;
  b.nv = 2;
  b.origin = Vec3(0.6, 2.3, -1.0);
  b.weft_axis = Vec3(0.0, 0.0, 1.0);
  return join(grid_mesh(a), grid_mesh(b));
}

// Expected crossings of crossing_strips(), counted by hand:
//  B's edges through z = 0: 5 vertical edges (x = 0.6 … 4.6) and 4 diagonals (x = 1.1 … 4.1),
//    each meeting A at y = 2.3 strictly inside one triangle of A: 9;
//  A's edges through y = 2.3 inside B's x-range (0.6, 4.6): edges (i,2)–(i,3) at x = i for
//    i = 1…4 and diagonals (i,2)–(i+1,3) at x = i + 0.3 for i = 1…4, each strictly inside one
//    triangle of B: 8.
constexpr int crossing_strips_expected = 9 + 8;

Mesh scaled(Mesh m, double scale, const Vec3& shift) {
  m.x *= scale;
  m.x.rowwise() += shift.transpose();
  return m;
}

// An n×n sheet over the unit square with every vertex moved by a uniform random offset of up
// to `amplitude_m` per axis: with amplitude above the spacing it passes through itself often.
Mesh crumpled_sheet(Index n, double amplitude_m, unsigned seed) {
  GridSpec spec;
  spec.nu = spec.nv = n;
  Mesh m = grid_mesh(spec);
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> offset(-amplitude_m, amplitude_m);
  for (Eigen::Index v = 0; v < m.x.rows(); ++v)
    for (int k = 0; k < 3; ++k) m.x(v, k) += offset(generator);
  return m;
}

TEST(SegmentCrossesTriangle, AnalyticCases) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Vec3 inside(0.25, 0.25, 0.0), up(0, 0, 1);
  EXPECT_TRUE(segment_crosses_triangle(inside - up, inside + up, a, b, c));
  EXPECT_TRUE(segment_crosses_triangle(inside + up, inside - up, a, b, c));  // direction
  EXPECT_TRUE(segment_crosses_triangle(inside - up, inside + up, a, c, b));  // orientation
  // Oblique through the interior.
  EXPECT_TRUE(segment_crosses_triangle(Vec3(-1, -1, -1), Vec3(1.5, 1.5, 1), a, b, c));
  // Misses: outside the triangle, stops short, ends on the plane, lies in the plane.
  EXPECT_FALSE(segment_crosses_triangle(Vec3(0.8, 0.8, -1), Vec3(0.8, 0.8, 1), a, b, c));
  EXPECT_FALSE(segment_crosses_triangle(inside + 0.5 * up, inside + up, a, b, c));
  EXPECT_FALSE(segment_crosses_triangle(inside, inside + up, a, b, c));
  EXPECT_FALSE(segment_crosses_triangle(Vec3(-1, 0.2, 0), Vec3(2, 0.2, 0), a, b, c));
  // Grazing: through a vertex, through an edge's midpoint — not counted (documented rule).
  EXPECT_FALSE(segment_crosses_triangle(a - up, a + up, a, b, c));
  EXPECT_FALSE(segment_crosses_triangle(Vec3(0.5, 0, -1), Vec3(0.5, 0, 1), a, b, c));
  // Just inside an edge by 1e-6 of the size still counts.
  EXPECT_TRUE(segment_crosses_triangle(Vec3(0.5, 1e-6, -1), Vec3(0.5, 1e-6, 1), a, b, c));
  // Degenerate triangle.
  EXPECT_FALSE(segment_crosses_triangle(inside - up, inside + up, a, b, Vec3(2, 0, 0)));
}

TEST(UniqueEdges, GridHasWarpWeftAndDiagonalEdgesOnce) {
  GridSpec spec;
  spec.nu = 4;
  spec.nv = 3;
  const auto edges = unique_edges(grid_mesh(spec).triangles);
  // (nu−1)·nv warp + nu·(nv−1) weft + (nu−1)(nv−1) diagonals.
  EXPECT_EQ(edges.size(), std::size_t{3 * 3 + 4 * 2 + 3 * 2});
  for (const auto& e : edges) EXPECT_LT(e[0], e[1]);
}

TEST(SelfIntersection, FlatAndSmoothSheetsHaveNone) {
  GridSpec spec;
  spec.nu = spec.nv = 33;
  Mesh m = grid_mesh(spec);
  EXPECT_EQ(crossings(m).size(), 0u);
  // A smooth wave, 10 cm high over 1 m: curved but not self-intersecting.
  for (Eigen::Index v = 0; v < m.x.rows(); ++v)
    m.x(v, 2) += 0.1 * std::sin(6.0 * m.x(v, 0)) * std::cos(4.0 * m.x(v, 1));
  EXPECT_EQ(crossings(m).size(), 0u);
}

TEST(SelfIntersection, CrossingStripsGiveTheHandCount) {
  const Mesh m = crossing_strips();
  const auto found = crossings(m);
  EXPECT_EQ(static_cast<int>(found.size()), crossing_strips_expected);
  // Each crossing edge goes through exactly one triangle (no crossing on a shared boundary).
  for (std::size_t k = 1; k < found.size(); ++k) EXPECT_NE(found[k].edge, found[k - 1].edge);
  // Pulling B up out of A removes every crossing.
  Mesh apart = m;
  apart.x.bottomRows(10).col(2).array() += 1.5;
  EXPECT_EQ(crossings(apart).size(), 0u);
}

TEST(SelfIntersection, InvariantUnderScaleAndTranslation) {
  const Mesh strips = crossing_strips();
  const Mesh crumpled = crumpled_sheet(12, 0.1, 7);
  const auto strips_reference = crossings(strips);
  const auto crumpled_reference = crossings(crumpled);
  ASSERT_GT(crumpled_reference.size(), 0u);
  for (const double scale : {1e-3, 1.0, 1e3}) {
    const Vec3 shift = scale * Vec3(3.25, -1.5, 0.75);
    EXPECT_EQ(crossings(scaled(strips, scale, shift)), strips_reference) << "scale " << scale;
    EXPECT_EQ(crossings(scaled(crumpled, scale, shift)), crumpled_reference) << "scale " << scale;
  }
}

TEST(SelfIntersection, HashedEqualsBruteForceOnCrumpledSheets) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    for (const double amplitude_m : {0.02, 0.1, 0.3}) {  // spacing is 1/15 m
      const Mesh m = crumpled_sheet(16, amplitude_m, seed);
      const auto edges = unique_edges(m.triangles);
      const auto hashed = find_edge_triangle_crossings(m.x, m.triangles, edges);
      const auto brute = find_edge_triangle_crossings_brute_force(m.x, m.triangles, edges);
      EXPECT_EQ(hashed, brute) << "seed " << seed << ", amplitude " << amplitude_m;
      if (amplitude_m >= 0.1) {
        EXPECT_GT(hashed.size(), 0u) << "seed " << seed;
      }
      EXPECT_EQ(count_edge_triangle_crossings(m.x, m.triangles, edges),
                static_cast<Index>(hashed.size()));
    }
  }
}

TEST(SelfIntersection, RejectsBadInput) {
  Mesh m = crossing_strips();
  auto edges = unique_edges(m.triangles);
  edges.push_back({0, static_cast<Index>(m.x.rows())});
  EXPECT_THROW(count_edge_triangle_crossings(m.x, m.triangles, edges), std::invalid_argument);
  edges.pop_back();
  m.x(3, 1) = std::nan("");
  EXPECT_THROW(count_edge_triangle_crossings(m.x, m.triangles, edges), std::invalid_argument);
}

// Random boxes of sizes from tiny to larger than the whole scene (those take the oversized list).
std::vector<Aabb> random_boxes(int count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Aabb> boxes;
  for (int i = 0; i < count; ++i) {
    const Vec3 lo(unit(generator), unit(generator), unit(generator));
    const double size = std::pow(10.0, -3.0 + 3.5 * unit(generator));  // 1 mm … 3 m
    const Vec3 extent(size * unit(generator), size * unit(generator), size * unit(generator));
    boxes.push_back({lo - Vec3::Constant(0.5), lo - Vec3::Constant(0.5) + extent});
  }
  // Two boxes touching a third exactly on a face: closed boxes overlap.
  boxes.push_back({Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1)});
  boxes.push_back({Vec3(0.1, 0, 0), Vec3(0.2, 0.1, 0.1)});
  return boxes;
}

TEST(SpatialHash, ReturnsExactlyTheOverlappingBoxesInAnyOrder) {
  const std::vector<Aabb> boxes = random_boxes(400, 11);
  const std::vector<Aabb> queries = random_boxes(200, 12);
  // The same boxes shuffled: box permutation[i] of `boxes` is box i of `shuffled_boxes`.
  std::vector<Index> permutation(boxes.size());
  for (std::size_t i = 0; i < permutation.size(); ++i) permutation[i] = static_cast<Index>(i);
  std::shuffle(permutation.begin(), permutation.end(), std::mt19937(13));
  std::vector<Aabb> shuffled_boxes;
  for (const Index i : permutation) shuffled_boxes.push_back(boxes[static_cast<std::size_t>(i)]);
  const SpatialHash forward(0.05, boxes);
  const SpatialHash shuffled(0.05, shuffled_boxes);

  std::size_t total = 0;
  for (const Aabb& q : queries) {
    std::vector<Index> expected;
    for (std::size_t i = 0; i < boxes.size(); ++i)
      if (boxes_overlap(boxes[i], q)) expected.push_back(static_cast<Index>(i));
    EXPECT_EQ(forward.query(q), expected);
    std::vector<Index> found = shuffled.query(q);
    EXPECT_TRUE(std::is_sorted(found.begin(), found.end()));
    for (Index& i : found) i = permutation[static_cast<std::size_t>(i)];
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
    total += expected.size();
  }
  EXPECT_GT(total, queries.size());  // the comparison is not vacuous
  // A point on the shared face of the two touching boxes finds both.
  const std::vector<Index> at_face =
      forward.query(Aabb{Vec3(0.1, 0.05, 0.05), Vec3(0.1, 0.05, 0.05)});
  const auto last = static_cast<Index>(boxes.size()) - 1;
  EXPECT_TRUE(std::count(at_face.begin(), at_face.end(), last - 1) == 1 &&
              std::count(at_face.begin(), at_face.end(), last) == 1);
}

TEST(SpatialHash, RejectsBadCellSizeAndBoxes) {
  const std::vector<Aabb> fine{Aabb{Vec3(0, 0, 0), Vec3(1, 1, 1)}};
  EXPECT_THROW(SpatialHash(0.0, fine), std::invalid_argument);
  EXPECT_THROW(SpatialHash(std::nan(""), fine), std::invalid_argument);
  EXPECT_THROW(SpatialHash(1.0, {Aabb{Vec3(1, 0, 0), Vec3(0, 1, 1)}}), std::invalid_argument);
  EXPECT_THROW(SpatialHash(1.0, {Aabb{Vec3(0, 0, 0), Vec3(std::nan(""), 1, 1)}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
