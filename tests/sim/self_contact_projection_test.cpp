// Self-contacts inside fast projection (sim/collision/self_contact_rows.h,
// sim/constraints/contact_projection.h): a layer pushed through another within a step comes
// back with every edge at its length, and rows that hold change nothing. Not yet used by the
// simulator: docs/collisions.md says what wiring it into a step measured.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/collision/self_contact_rows.h"
#include "sim/collision/self_intersection.h"
#include "sim/constraints/contact_projection.h"
#include "sim/constraints/fast_projection.h"

namespace weft::sim {
namespace {

// A 1 m sheet of n × n vertices folded in half across warp: the half beyond the middle column
// lies gap_m above the other, turned back. Edges keep their rest lengths except the few across
// the fold.
Matrix3X folded(const ClothMesh& mesh, double gap_m) {
  Matrix3X x = mesh.rest_positions;
  const Index mid = mesh.nu / 2;
  const double dx = 1.0 / static_cast<double>(mesh.nu - 1);
  for (Index j = 0; j < mesh.nv; ++j)
    for (Index i = mid + 1; i < mesh.nu; ++i) {
      const Index v = mesh.index(i, j);
      x(v, 0) = x(mesh.index(2 * mid - i, j), 0);
      x(v, 2) = gap_m;
    }
  // The fold column halfway up, so the edges across it are equally stretched.
  for (Index j = 0; j < mesh.nv; ++j) x(mesh.index(mid, j), 0) += 0.5 * dx, x(mesh.index(mid, j), 2) = 0.5 * gap_m;
  return x;
}

ClothMesh sheet_at_height(Index n, double z_m) {
  GridSpec grid;
  grid.nu = grid.nv = n;
  grid.origin = Vec3(-0.5, -0.5, z_m);
  return make_grid(grid);
}

Index crossings(const Matrix3X& x, const ClothMesh& mesh) {
  const auto triangles = mesh.triangles();
  return count_edge_triangle_crossings(x, triangles, unique_edges(triangles));
}

// A patch of the top layer of a fold 6 mm thick moves 10 mm down within one step, through the
// bottom layer (stretching the edges around it by 1.3 %). The rows gathered at the step's start keep each
// pair on its side: the projection with them ends with the layers apart by at least 3/4 of the
// contact distance, no crossing and every edge within the tolerance; the projection without
// them leaves the crossings.
TEST(ContactProjection, ALayerPushedThroughWithinAStepGoesBackWithEdgesAtLength) {
  const ClothMesh mesh = sheet_at_height(17, 0.0);
  const Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(mesh.vertex_count());
  const double distance_m = 2e-3, edge_tolerance = 1e-3;
  const Matrix3X x_start = folded(mesh, 6e-3);
  Matrix3X x_end = x_start;
  for (Index j = 4; j <= 12; ++j)
    for (Index i = mesh.nu / 2 + 2; i < mesh.nu; ++i) x_end(mesh.index(i, j), 2) -= 10e-3;
  ASSERT_EQ(crossings(x_start, mesh), 0);
  ASSERT_GT(crossings(x_end, mesh), 0) << "the step does not pass through: no test";

  SelfContactRows rows(mesh, distance_m, 0.0);
  rows.gather(x_start, x_end, inv_mass, 0.5 * rows.mean_edge_m());
  ASSERT_FALSE(rows.rows().empty());
  const std::vector<EdgeConstraint> edges =
      make_edge_constraints(mesh, ConstrainedEdges::warp_weft, inv_mass);

  Matrix3X plain = x_end;
  const ProjectionResult plain_result =
      FastProjection(edges, inv_mass, ProjectionSettings{}, default_sparse_backend()).project(plain);
  EXPECT_TRUE(plain_result.converged);
  EXPECT_GT(crossings(plain, mesh), 0) << "the projection alone already undoes the crossing";

  ContactProjection projection(edges, edge_tolerance, 100, default_sparse_backend());
  Matrix3X x = x_end;
  const ContactProjectionResult r = projection.project(x, inv_mass, rows.rows(), distance_m, rows.lateral_m());
  std::printf("%zu rows, %d active, %d iterations, strain %.2e, closest row %.3f mm\n",
              rows.rows().size(), r.active_rows, r.projection.iterations, r.projection.max_strain,
              1e3 * r.worst_gap_m);
  EXPECT_TRUE(r.projection.converged);
  EXPECT_LE(max_edge_strain(edges, x), edge_tolerance);
  EXPECT_GE(rows.worst_violation(x), -ContactProjection::contact_tolerance * distance_m);
  EXPECT_EQ(crossings(x, mesh), 0);
  // Mass-weighted projection with equal masses keeps the centre of mass.
  EXPECT_NEAR((x.colwise().mean() - x_end.colwise().mean()).norm(), 0.0, 1e-9);
}

// No row is violated, so the rows change nothing: the result is plain fast projection's.
TEST(ContactProjection, RowsNotViolatedLeaveTheProjectionAlone) {
  const ClothMesh mesh = sheet_at_height(9, 0.0);
  const Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(mesh.vertex_count());
  const Matrix3X x_start = folded(mesh, 20e-3);
  SelfContactRows rows(mesh, 2e-3, 0.0);
  rows.gather(x_start, x_start, inv_mass, 0.5 * rows.mean_edge_m());
  EXPECT_EQ(rows.worst_violation(x_start), 0.0);
  const auto edges = make_edge_constraints(mesh, ConstrainedEdges::warp_weft, inv_mass);
  Matrix3X x = x_start;
  const ContactProjectionResult r =
      ContactProjection(edges, 1e-3, 100, default_sparse_backend()).project(x, inv_mass, rows.rows(), 2e-3, rows.lateral_m());
  EXPECT_EQ(r.active_rows, 0);
  EXPECT_LE(max_edge_strain(edges, x), 1e-3);
}

}  // namespace
}  // namespace weft::sim
