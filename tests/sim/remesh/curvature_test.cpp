// Curvature estimate (sim/remesh/curvature.h): analytic surfaces from flat sheets.

#include "sim/remesh/curvature.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/remesh/mesh_topology.h"
#include "tests/sim/remesh/test_meshes.h"

namespace weft::sim::remesh {
namespace {

using testing::deform;
using testing::grid_mesh;
using testing::on_cylinder;

// Vertices whose two-ring stencil does not reach the boundary: at least three rings inside.
std::vector<Index> deep_interior(Index nu, Index nv) {
  std::vector<Index> out;
  for (Index j = 3; j + 3 < nv; ++j)
    for (Index i = 3; i + 3 < nu; ++i) out.push_back(j * nu + i);
  return out;
}

double worst_relative_error(const Eigen::VectorXd& kappa, const std::vector<Index>& vertices,
                            double expected) {
  double worst = 0.0;
  for (Index v : vertices) worst = std::max(worst, std::abs(kappa(v) - expected) / expected);
  return worst;
}

TEST(Curvature, PlaneGivesZeroUnderRotationAndStretch) {
  const auto m = grid_mesh(0.3, 0.2, 16, 11);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Matrix3X x = deform(m.material, [&](double u, double v) {
    return Vec3(R * Vec3(1.1 * u + 0.2 * v, 0.9 * v, 0.0) + Vec3(0.5, -1, 2));
  });
  const Eigen::VectorXd kappa = vertex_curvature(m.material, m.triangles, x);
  EXPECT_LT(kappa.maxCoeff(), 1e-9);  // every vertex, boundary and corners included
}

TEST(Curvature, CylinderGivesOneOverRadiusAtInteriorVertices) {
  // h/R = 0.05: a 30 × 20 cm sheet with 5 mm cells rolled on a cylinder of radius 10 cm.
  const double R = 0.1;
  const Index nu = 61, nv = 41;
  const auto m = grid_mesh(0.3, 0.2, nu, nv);
  const Eigen::VectorXd kappa = vertex_curvature(
      m.material, m.triangles,
      deform(m.material, [&](double u, double v) { return on_cylinder(u, v, R); }));
  EXPECT_LT(worst_relative_error(kappa, deep_interior(nu, nv), 1.0 / R), 0.02);
}

TEST(Curvature, CylinderAtAnAngleToTheWarpAndStretchedGivesOneOverRadius) {
  // The fold's axis at 35° to v, and the cloth stretched 8 % along the fold's direction:
  // the shape operator I⁻¹ II is independent of both.
  const double R = 0.1, angle = 35.0 * M_PI / 180.0;
  const Index nu = 61, nv = 61;
  const auto m = grid_mesh(0.25, 0.25, nu, nv);
  const Eigen::VectorXd kappa =
      vertex_curvature(m.material, m.triangles, deform(m.material, [&](double u, double v) {
                         const double s = 1.08 * (std::cos(angle) * u + std::sin(angle) * v);
                         const double t = -std::sin(angle) * u + std::cos(angle) * v;
                         return on_cylinder(s, t, R);
                       }));
  EXPECT_LT(worst_relative_error(kappa, deep_interior(nu, nv), 1.0 / R), 0.02);
}

TEST(Curvature, SphereGivesOneOverRadius) {
  // A 12 × 12 cm sheet laid on a sphere of radius 10 cm by the azimuthal equidistant map
  // (lengths along meridians kept, parallels stretched: the metric I is not the identity).
  const double R = 0.1;
  const Index n = 49;
  const auto m = grid_mesh(0.12, 0.12, n, n, -0.06, -0.06);
  const Eigen::VectorXd kappa = vertex_curvature(
      m.material, m.triangles, deform(m.material, [&](double u, double v) { return testing::on_sphere(u, v, R); }));
  EXPECT_LT(worst_relative_error(kappa, deep_interior(n, n), 1.0 / R), 0.02);
}

TEST(Curvature, CylinderErrorFallsWithTheSquareOfTheSpacing) {
  const double R = 0.1;
  std::vector<double> errors;
  for (Index n : {16, 31, 61}) {  // spacings 2, 1, 0.5 cm on a 30 cm sheet
    const auto m = grid_mesh(0.3, 0.3, n, n);
    const Eigen::VectorXd kappa = vertex_curvature(
        m.material, m.triangles,
        deform(m.material, [&](double u, double v) { return on_cylinder(u, v, R); }));
    errors.push_back(worst_relative_error(kappa, deep_interior(n, n), 1.0 / R));
  }
  // Second order: each halving divides the error by about 4 (at least 3 here).
  EXPECT_GT(errors[0] / errors[1], 3.0) << errors[0] << " " << errors[1];
  EXPECT_GT(errors[1] / errors[2], 3.0) << errors[1] << " " << errors[2];
}

TEST(Curvature, PrincipalCurvaturesOfASaddle) {
  Eigen::Matrix2d I = Eigen::Matrix2d::Identity(), II;
  II << 2.0, 0.0, 0.0, -3.0;
  const Eigen::Vector2d k = principal_curvatures(I, II);
  EXPECT_DOUBLE_EQ(k(0), 2.0);
  EXPECT_DOUBLE_EQ(k(1), -3.0);
}

TEST(Curvature, MismatchedPositionsAreAnError) {
  const auto m = grid_mesh(0.1, 0.1, 3, 3);
  EXPECT_THROW(vertex_curvature(m.material, m.triangles, Matrix3X::Zero(4, 3)),
               std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim::remesh
