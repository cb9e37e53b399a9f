// Point location and transfer of per-vertex quantities to a new mesh (sim/remesh/transfer.h).

#include "sim/remesh/transfer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/remesh/mesh_topology.h"
#include "sim/remesh/mesher.h"
#include "sim/remesh/point_locator.h"
#include "tests/sim/remesh/test_meshes.h"

namespace weft::sim::remesh {
namespace {

using testing::grid_mesh;
using testing::PlainMesh;

PlainMesh notched_sheet() {
  return grid_mesh(0.3, 0.2, 16, 11, 0.0, 0.0,
                   [](Index i, Index j) { return !(i >= 6 && i < 9 && j >= 4 && j < 7); });
}

double uniform_size(const Vec2& p) {
  return 0.006 + 0.02 * p.x();
}

TEST(PointLocator, FindsPointsOnVerticesEdgesAndTheBoundary) {
  const PlainMesh m = notched_sheet();
  const PointLocator locator(m.material, m.triangles);
  // Every vertex and every edge midpoint (boundary ones included) lies in a triangle holding it.
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = m.material.row(m.triangles(t, k)),
                 b = m.material.row(m.triangles(t, (k + 1) % 3));
      for (const Vec2& p : {a, Vec2(0.5 * (a + b)), Vec2(0.3 * a + 0.7 * b)}) {
        const Location at = locator.locate(p);
        ASSERT_GE(at.triangle, 0);
        EXPECT_GE(std::min({at.barycentric[0], at.barycentric[1], at.barycentric[2]}), -1e-15);
        EXPECT_TRUE(locator.contains(p));
      }
    }
  EXPECT_FALSE(locator.contains(Vec2(0.15, 0.1)));        // inside the hole
  EXPECT_FALSE(locator.contains(Vec2(-0.01, 0.1)));       // left of the sheet
  EXPECT_TRUE(locator.contains(Vec2(0.3 + 1e-14, 0.1)));  // a rounding error outside
  EXPECT_FALSE(locator.contains(Vec2(NAN, 0.1)));
  EXPECT_THROW(locator.locate(Vec2(0.1, INFINITY)), std::invalid_argument);
}

TEST(Transfer, AnAffineFieldIsTransferredExactly) {
  const PlainMesh old = notched_sheet();
  Eigen::Matrix<double, 3, 2> A;
  A << 0.9, 0.3, -0.2, 1.1, 0.5, -0.7;
  const Vec3 b(0.1, -2.0, 1.5);
  const auto field = [&](const Matrix2X& X) {
    Matrix3X x(X.rows(), 3);
    for (Eigen::Index v = 0; v < X.rows(); ++v)
      x.row(v) = (A * X.row(v).transpose() + b).transpose();
    return x;
  };
  const MeshResult r = mesh_domain(old.material, old.triangles, {17}, uniform_size);
  const PointLocator locator(old.material, old.triangles);
  const TransferMap map = make_transfer_map(locator, r.material, r.new_to_old);
  const Matrix3X moved = transfer(map, old.triangles, field(old.material));
  EXPECT_LT((moved - field(r.material)).cwiseAbs().maxCoeff(), 1e-12);
  // Any width: five affine columns.
  MatrixX wide(old.material.rows(), 5), expected(r.material.rows(), 5);
  for (int c = 0; c < 5; ++c) {
    wide.col(c) = (c + 1.0) * old.material.col(0) - c * old.material.col(1) +
                  Eigen::VectorXd::Constant(old.material.rows(), 0.25 * c);
    expected.col(c) = (c + 1.0) * r.material.col(0) - c * r.material.col(1) +
                      Eigen::VectorXd::Constant(r.material.rows(), 0.25 * c);
  }
  EXPECT_LT((transfer(map, old.triangles, wide) - expected).cwiseAbs().maxCoeff(), 1e-12);
}

// Σ ½ k (|x_i − x_j| − L_ij)² over the edges, L from the material coordinates, k = 1 N/m: the
// simplest elastic energy of a mesh (the cloth models need the simulator; this needs only the
// arrays).
double spring_energy(const Matrix2X& material, const Triangles& triangles, const Matrix3X& x) {
  double energy = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index i = triangles(t, k), j = triangles(t, (k + 1) % 3);
      const double strain =
          (x.row(i) - x.row(j)).norm() - (material.row(i) - material.row(j)).norm();
      energy += 0.25 * strain * strain;  // each interior edge is seen twice
    }
  return energy;
}

TEST(Transfer, AFlatClothAtRestStaysAtRest) {
  const PlainMesh old = notched_sheet();
  // The rest shape laid flat at z = 1 m, turned 30° about z; not moving.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 6.0, Vec3::UnitZ()).toRotationMatrix();
  const Matrix3X x = testing::deform(
      old.material, [&](double u, double v) { return Vec3(R * Vec3(u, v, 0.0) + Vec3(0, 0, 1)); });
  const Matrix3X velocity = Matrix3X::Zero(old.material.rows(), 3);
  ASSERT_LT(spring_energy(old.material, old.triangles, x), 1e-30);
  const MeshResult r = mesh_domain(old.material, old.triangles, {}, uniform_size);
  const TransferMap map =
      make_transfer_map(PointLocator(old.material, old.triangles), r.material, r.new_to_old);
  EXPECT_TRUE((transfer(map, old.triangles, velocity).array() == 0.0).all());
  // Energy after the remesh, J: rounding only (remesh_bench: 5.5e-32 J on a flat sheet).
  EXPECT_LT(spring_energy(r.material, r.triangles, transfer(map, old.triangles, x)), 1e-28);
}

}  // namespace
}  // namespace weft::sim::remesh
