// CGAL Delaunay refinement of a material domain with a size field (sim/remesh/mesher.h).

#include "sim/remesh/mesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "sim/remesh/mesh_topology.h"
#include "tests/sim/remesh/test_meshes.h"

namespace weft::sim::remesh {
namespace {

using testing::area2;
using testing::grid_mesh;
using testing::PlainMesh;

// A 40 × 30 cm sheet of 2 cm cells with a 10 × 6 cm hole and a notch cut from one side.
PlainMesh holed_sheet() {
  return grid_mesh(0.4, 0.3, 21, 16, 0.0, 0.0, [](Index i, Index j) {
    const bool hole = i >= 8 && i < 13 && j >= 6 && j < 9;
    const bool notch = i >= 15 && j >= 12;
    return !hole && !notch;
  });
}

// A field 4 mm fine along the line u = 0.1, growing linearly to 4 cm away from it.
double graded(const Vec2& p) {
  return std::min(0.04, 0.004 + 0.3 * std::abs(p.x() - 0.1));
}

struct SizeMeasure {
  double worst_ratio = 0.0;   // max over triangles of longest edge / h(centroid)
  double median_ratio = 0.0;  // median of the same
};

SizeMeasure measure(const MeshResult& r, const SizeFunction& size) {
  std::vector<double> ratio;
  for (Eigen::Index t = 0; t < r.triangles.rows(); ++t) {
    double longest = 0.0;
    Vec2 centroid = Vec2::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = r.material.row(r.triangles(t, k)),
                 b = r.material.row(r.triangles(t, (k + 1) % 3));
      longest = std::max(longest, (b - a).norm());
      centroid += a / 3.0;
    }
    ratio.push_back(longest / size(centroid));
  }
  std::sort(ratio.begin(), ratio.end());
  return {ratio.back(), ratio[ratio.size() / 2]};
}

TEST(Mesher, MeetsAGradedSizeFieldWithinAFactor) {
  const PlainMesh old = holed_sheet();
  const MeshResult r = mesh_domain(old.material, old.triangles, {}, graded);
  const SizeMeasure m = measure(r, graded);
  // Never coarser than asked; not much finer either: Delaunay refinement stops once every
  // triangle is small enough, so typical triangles are between half and all of the target.
  EXPECT_LE(m.worst_ratio, 1.0);
  EXPECT_GE(m.median_ratio, 0.5);
  // Graded: the triangles within 1 cm of the fine line are much smaller than those far from it.
  double near = 0.0, far = 0.0;
  int n_near = 0, n_far = 0;
  for (Eigen::Index t = 0; t < r.triangles.rows(); ++t) {
    const Vec2 c = (r.material.row(r.triangles(t, 0)) + r.material.row(r.triangles(t, 1)) +
                    r.material.row(r.triangles(t, 2)))
                       .transpose() /
                   3.0;
    const double a =
        std::abs(signed_area2(r.material.row(r.triangles(t, 0)), r.material.row(r.triangles(t, 1)),
                              r.material.row(r.triangles(t, 2))));
    if (std::abs(c.x() - 0.1) < 0.01) near += a, ++n_near;
    if (c.x() > 0.3) far += a, ++n_far;
  }
  EXPECT_GT((far / n_far) / (near / n_near), 10.0);
}

TEST(Mesher, KeepsTheDomainItsBoundaryVerticesAndPins) {
  const PlainMesh old = holed_sheet();
  const std::vector<Index> pins{5 * 21 + 3, 10 * 21 + 17, 0};  // two interior, one corner
  const MeshResult r = mesh_domain(old.material, old.triangles, pins, graded);
  // Same area: the domain (outline, hole, notch) is the old one.
  EXPECT_NEAR(area2(r.material, r.triangles), area2(old.material, old.triangles), 1e-13);
  // Every boundary vertex and pin is a new vertex, at bit-identical (u, v).
  std::set<Index> must_keep(pins.begin(), pins.end());
  for (const auto& e : boundary_edges(old.triangles)) must_keep.insert({e[0], e[1]});
  std::set<Index> kept;
  for (size_t i = 0; i < r.new_to_old.size(); ++i) {
    const Index o = r.new_to_old[i];
    if (o < 0) continue;
    kept.insert(o);
    EXPECT_EQ(r.material(static_cast<Eigen::Index>(i), 0), old.material(o, 0));
    EXPECT_EQ(r.material(static_cast<Eigen::Index>(i), 1), old.material(o, 1));
  }
  EXPECT_EQ(kept, must_keep);
  // The new boundary is the old one: the same length (split, never moved).
  const auto length = [](const Matrix2X& x, const Triangles& t) {
    double sum = 0.0;
    for (const auto& e : boundary_edges(t)) sum += (x.row(e[0]) - x.row(e[1])).norm();
    return sum;
  };
  EXPECT_NEAR(length(r.material, r.triangles), length(old.material, old.triangles), 1e-12);
}

TEST(Mesher, TrianglesHavePositiveAreaConsistentOrientationAndNoSmallAngles) {
  PlainMesh old = holed_sheet();
  for (int flip = 0; flip < 2; ++flip) {
    if (flip) old.triangles.col(1).swap(old.triangles.col(2));  // clockwise input
    const MeshResult r = mesh_domain(old.material, old.triangles, {}, graded);
    EXPECT_EQ(orientation(r.material, r.triangles), orientation(old.material, old.triangles));
    double smallest_angle = 180.0;
    for (Eigen::Index t = 0; t < r.triangles.rows(); ++t) {
      const Vec2 a = r.material.row(r.triangles(t, 0)), b = r.material.row(r.triangles(t, 1)),
                 c = r.material.row(r.triangles(t, 2));
      EXPECT_NE(signed_area2(a, b, c), 0.0);
      const auto angle = [](Vec2 p, Vec2 q, Vec2 s) {
        return std::acos((q - p).normalized().dot((s - p).normalized())) * 180.0 / M_PI;
      };
      smallest_angle = std::min({smallest_angle, angle(a, b, c), angle(b, c, a), angle(c, a, b)});
    }
    // The input's own corners are right angles, so nothing forces an angle below the bound.
    EXPECT_GE(smallest_angle, 20.0 - 1e-9);
    // Every edge has at most two triangles, and every vertex is used.
    EXPECT_NO_THROW(boundary_edges(r.triangles));
    std::vector<char> used(static_cast<size_t>(r.material.rows()), 0);
    for (Eigen::Index t = 0; t < r.triangles.rows(); ++t)
      for (int k = 0; k < 3; ++k) used[static_cast<size_t>(r.triangles(t, k))] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
  }
}

TEST(Mesher, SameInputGivesTheSameBits) {
  const PlainMesh old = holed_sheet();
  const MeshResult a = mesh_domain(old.material, old.triangles, {30}, graded);
  const MeshResult b = mesh_domain(old.material, old.triangles, {30}, graded);
  ASSERT_EQ(a.material.rows(), b.material.rows());
  ASSERT_EQ(a.triangles.rows(), b.triangles.rows());
  EXPECT_EQ(0, std::memcmp(a.material.data(), b.material.data(),
                           sizeof(double) * static_cast<size_t>(a.material.size())));
  EXPECT_TRUE(a.triangles == b.triangles);
  EXPECT_EQ(a.new_to_old, b.new_to_old);
}

TEST(Mesher, BadInputIsAnErrorNamingTheItem) {
  const PlainMesh old = grid_mesh(0.1, 0.1, 3, 3);
  const auto uniform = [](const Vec2&) { return 0.02; };
  const auto message = [&](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] {
              mesh_domain(old.material, old.triangles, {9}, uniform);
            }).find("pinned vertex 9"),
            std::string::npos);
  EXPECT_NE(message([&] {
              mesh_domain(old.material, old.triangles, {}, [](const Vec2&) { return 0.0; });
            }).find("size field"),
            std::string::npos);
  EXPECT_NE(message([&] {
              mesh_domain(
                  old.material, old.triangles, {}, [](const Vec2&) { return 1e-4; },
                  MesherParams{20.0, 1000});
            }).find("max_vertices"),
            std::string::npos);
  Triangles degenerate = old.triangles;
  degenerate.row(0) << 0, 1, 2;  // three vertices on the line v = 0
  EXPECT_NE(message([&] {
              mesh_domain(old.material, degenerate, {}, uniform);
            }).find("triangle 0 has zero material area"),
            std::string::npos);
  Triangles nonmanifold(3, 3);
  nonmanifold << 0, 1, 4, 0, 1, 3, 0, 1, 5;  // edge (0, 1) in three triangles
  EXPECT_NE(
      message([&] { mesh_domain(old.material, nonmanifold, {}, uniform); }).find("non-manifold"),
      std::string::npos);
}

}  // namespace
}  // namespace weft::sim::remesh
