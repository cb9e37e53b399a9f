// The quadratic transfer of positions (sim/remesh/transfer.h transfer_quadratic): new vertices
// on the curved surface, not on the old mesh's chords. It reproduces what the linear transfer
// reproduces (affine fields, a flat cloth at rest), and its distance to the true surface falls
// with the cube of the old spacing, where the linear one's falls with the square.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "sim/remesh/curvature.h"
#include "sim/remesh/mesher.h"
#include "sim/remesh/point_locator.h"
#include "sim/remesh/remesh.h"
#include "sim/remesh/transfer.h"
#include "tests/sim/remesh/test_meshes.h"

namespace weft::sim::remesh {
namespace {

using testing::grid_mesh;
using testing::PlainMesh;

struct Transferred {
  Matrix2X material;  // the new mesh's
  Triangles triangles;
  Matrix3X linear, quadratic;  // the positions at its vertices
};

// The old mesh deformed by `map`, meshed anew with edges of at most `new_h` and no vertex kept
// but the boundary, positions transferred both ways.
Transferred transfer_both_ways(const PlainMesh& old,
                               const std::function<Vec3(double, double)>& map, double new_h) {
  const Matrix3X x = testing::deform(old.material, map);
  const MeshResult r =
      mesh_domain(old.material, old.triangles, {}, [&](const Vec2&) { return new_h; });
  const TransferMap tm =
      make_transfer_map(PointLocator(old.material, old.triangles), r.material, r.new_to_old);
  return {r.material, r.triangles, transfer(tm, old.triangles, x),
          transfer_quadratic(tm, old.material, old.triangles, x,
                             patch_second_derivatives(
                                 vertex_patches(old.material, old.triangles, x)))};
}

TEST(QuadraticTransfer, AnAffineFieldAndAFlatClothAtRestAreReproduced) {
  const PlainMesh old = grid_mesh(0.3, 0.2, 16, 11, 0.0, 0.0, [](Index i, Index j) {
    return !(i >= 6 && i < 9 && j >= 4 && j < 7);  // a hole
  });
  Eigen::Matrix<double, 3, 2> A;
  A << 0.9, 0.3, -0.2, 1.1, 0.5, -0.7;
  const Vec3 b(0.1, -2.0, 1.5);
  const auto affine = [&](double u, double v) { return Vec3(A * Vec2(u, v) + b); };
  const Transferred t = transfer_both_ways(old, affine, 0.007);
  EXPECT_LT((t.quadratic - testing::deform(t.material, affine)).cwiseAbs().maxCoeff(), 1e-12);

  // A flat cloth at rest: every new edge at its rest length to rounding.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 6.0, Vec3::UnitZ()).toRotationMatrix();
  const Transferred flat = transfer_both_ways(
      old, [&](double u, double v) { return Vec3(R * Vec3(u, v, 0.0) + Vec3(0, 0, 1)); }, 0.007);
  double worst = 0.0;
  for (Eigen::Index f = 0; f < flat.triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Index i = flat.triangles(f, k), j = flat.triangles(f, (k + 1) % 3);
      worst = std::max(worst, std::abs((flat.quadratic.row(i) - flat.quadratic.row(j)).norm() -
                                       (flat.material.row(i) - flat.material.row(j)).norm()));
    }
  EXPECT_LT(worst, 1e-15);
}

// Largest distance of the new vertices from a surface, metres.
double worst_distance(const Matrix3X& x, const std::function<double(const Vec3&)>& distance) {
  double worst = 0.0;
  for (Eigen::Index v = 0; v < x.rows(); ++v) worst = std::max(worst, distance(x.row(v)));
  return worst;
}

struct ChordErrors {
  double linear_m, quadratic_m;
};

// A 20 × 20 cm sheet on old cells of h, bent by `map`, remeshed at 0.4 h.
ChordErrors chord_errors(double h, const std::function<Vec3(double, double)>& map,
                         const std::function<double(const Vec3&)>& distance) {
  const auto n = static_cast<Index>(std::lround(0.2 / h)) + 1;
  const Transferred t = transfer_both_ways(grid_mesh(0.2, 0.2, n, n, -0.1, -0.1), map, 0.4 * h);
  return {worst_distance(t.linear, distance), worst_distance(t.quadratic, distance)};
}

// Linear: the chord's sagitta, up to d²/(8R) over a facet of width d ≤ √2 h, second order.
// Quadratic: third order, and at h/R = 0.1 more than ten times closer. Measured, R = 10 cm,
// h = 2 cm → 1 cm: cylinder, linear 0.50 → 0.125 mm, quadratic 10 → 0.64 µm; sphere, linear
// 0.99 → 0.25 mm, quadratic 34 → 2.8 µm.
void expect_third_order(const std::function<Vec3(double, double)>& map,
                        const std::function<double(const Vec3&)>& distance, double R) {
  const ChordErrors coarse = chord_errors(0.02, map, distance);
  const ChordErrors fine = chord_errors(0.01, map, distance);
  EXPECT_LT(coarse.linear_m, 2.0 * 0.02 * 0.02 / (8.0 * R));
  EXPECT_NEAR(coarse.linear_m / fine.linear_m, 4.0, 1.0);
  EXPECT_GT(coarse.quadratic_m / fine.quadratic_m, 6.0);
  EXPECT_LT(fine.quadratic_m, 0.1 * fine.linear_m);
}

TEST(QuadraticTransfer, NewVerticesLieOnACylinderToThirdOrder) {
  const double R = 0.1;
  expect_third_order([&](double u, double v) { return testing::on_cylinder(u, v, R); },
                     [&](const Vec3& x) { return std::abs(std::hypot(x.x(), x.z() - R) - R); },
                     R);
}

TEST(QuadraticTransfer, NewVerticesLieOnASphereToThirdOrder) {
  const double R = 0.1;
  expect_third_order([&](double u, double v) { return testing::on_sphere(u, v, R); },
                     [&](const Vec3& x) { return std::abs((x - Vec3(0, 0, R)).norm() - R); }, R);
}

}  // namespace
}  // namespace weft::sim::remesh
