// The mass-spring stiffnesses reproduce the continuum energies they stand for (seed 004), so
// that behaviour does not depend on the sampling.
#include "sim/mass_spring.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace weft::sim {
namespace {

Material test_material() {
  Material m;
  m.density_kg_m2 = 0.2;
  m.stretch_warp_N_m = 900.0;
  m.stretch_weft_N_m = 600.0;
  m.shear_N_m = 40.0;
  m.bend_warp_Nm = 8e-6;
  m.bend_weft_Nm = 5e-6;
  return m;
}

ClothMesh flat_grid(Index nu, Index nv, double su = 0.6, double sv = 0.45) {
  GridSpec spec;
  spec.size_u_m = su;
  spec.size_v_m = sv;
  spec.nu = nu;
  spec.nv = nv;
  spec.origin = Vec3::Zero();
  return make_grid(spec);
}

// Positions after the in-plane affine map (u, v) → F (u, v).
Matrix3X deformed(const ClothMesh& mesh, const Eigen::Matrix2d& F) {
  Matrix3X x = Matrix3X::Zero(mesh.vertex_count(), 3);
  for (Index k = 0; k < mesh.vertex_count(); ++k)
    x.row(k).head<2>() = (F * mesh.material_coords[k]).transpose();
  return x;
}

class MassSpringContinuum : public ::testing::TestWithParam<std::pair<Index, Index>> {};

TEST_P(MassSpringContinuum, UniaxialWarpStretchEnergyIsHalfYuEpsSquaredTimesArea) {
  const auto [nu, nv] = GetParam();
  const ClothMesh mesh = flat_grid(nu, nv);
  const Material m = test_material();
  const MassSpringModel model(mesh, m);
  const double eps = 1e-5, area = 0.6 * 0.45;
  Eigen::Matrix2d F;
  F << 1 + eps, 0, 0, 1;
  EXPECT_NEAR(model.energy(deformed(mesh, F)) / (0.5 * m.stretch_warp_N_m * eps * eps * area), 1.0, 1e-4);
  F << 1, 0, 0, 1 + eps;
  EXPECT_NEAR(model.energy(deformed(mesh, F)) / (0.5 * m.stretch_weft_N_m * eps * eps * area), 1.0, 1e-4);
}

TEST_P(MassSpringContinuum, PureShearEnergyIsHalfGGammaSquaredTimesArea) {
  const auto [nu, nv] = GetParam();
  const ClothMesh mesh = flat_grid(nu, nv);
  const Material m = test_material();
  const MassSpringModel model(mesh, m);
  const double gamma = 1e-5, area = 0.6 * 0.45;
  Eigen::Matrix2d F;
  F << 1, gamma / 2, gamma / 2, 1;
  EXPECT_NEAR(model.energy(deformed(mesh, F)) / (0.5 * m.shear_N_m * gamma * gamma * area), 1.0, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, MassSpringContinuum,
                         ::testing::Values(std::pair{2, 2}, std::pair{5, 5}, std::pair{9, 17},
                                           std::pair{33, 25}, std::pair{64, 64}));

// Warp lines wrapped on a cylinder of radius R with chords of exactly the rest length: only the
// warp bending springs are loaded, and their energy tends to ½ B κ² A as the grid is refined.
double cylinder_bend_energy(Index n, double radius, double* exact_discrete) {
  const double su = 0.3, sv = 0.2;
  const ClothMesh mesh = flat_grid(n, n, su, sv);
  const Material m = test_material();
  const double hu = su / (n - 1);
  const double alpha = 2.0 * std::asin(hu / (2.0 * radius));  // turning angle per vertex
  Matrix3X x(mesh.vertex_count(), 3);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i)
      x.row(mesh.index(i, j)) << radius * std::sin(i * alpha), mesh.material_coords[mesh.index(i, j)].y(),
          radius * (1 - std::cos(i * alpha));
  const double kappa = alpha / hu;
  *exact_discrete = 0.5 * m.bend_warp_Nm * kappa * kappa * (n - 2) * hu * sv;
  return MassSpringModel(mesh, m).energy(x);
}

TEST(MassSpringBending, CylinderEnergyConvergesToHalfBKappaSquaredArea) {
  const double radius = 0.05, continuum = 0.5 * 8e-6 / (radius * radius) * 0.3 * 0.2;
  double previous_error = 1e9;
  for (Index n : {9, 17, 33, 65}) {
    double discrete = 0.0;
    const double e = cylinder_bend_energy(n, radius, &discrete);
    EXPECT_NEAR(e / discrete, 1.0, 1e-9) << "n = " << n;  // only the bending springs are loaded
    const double error = std::abs(e / continuum - 1.0);
    EXPECT_LT(error, previous_error) << "n = " << n;
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.02);
}

TEST(MassSpringModel, RigidMotionsHaveNoEnergyAndNoForce) {
  const ClothMesh mesh = flat_grid(12, 9);
  const MassSpringModel model(mesh, test_material());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  Matrix3X x = mesh.rest_positions * R.transpose();
  x.rowwise() += Eigen::RowVector3d(3.0, -1.0, 0.5);
  EXPECT_LT(model.energy(x), 1e-20);
  Matrix3X f = Matrix3X::Zero(x.rows(), 3);
  model.add_forces(x, f);
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-9);
}

TEST(MassSpringModel, ForcesAreMinusTheEnergyGradient) {
  const ClothMesh mesh = flat_grid(5, 4);
  const MassSpringModel model(mesh, test_material());
  Matrix3X x = mesh.rest_positions;
  for (Index k = 0; k < x.rows(); ++k)  // a smooth, non-trivial deformation
    x.row(k) += 0.01 * Eigen::RowVector3d(std::sin(7.0 * k), std::cos(3.0 * k), std::sin(k * 1.3));
  Matrix3X f = Matrix3X::Zero(x.rows(), 3);
  model.add_forces(x, f);
  const double h = 1e-7;
  for (Index k = 0; k < x.rows(); ++k) {
    for (int c = 0; c < 3; ++c) {
      Matrix3X xp = x, xm = x;
      xp(k, c) += h;
      xm(k, c) -= h;
      const double fd = -(model.energy(xp) - model.energy(xm)) / (2 * h);
      EXPECT_NEAR(f(k, c), fd, 1e-5 * (1.0 + std::abs(fd))) << "vertex " << k << " axis " << c;
    }
  }
}

TEST(MassSpringModel, RejectsShearStifferThanStretchAtTheCellAspect) {
  Material m = test_material();
  m.shear_N_m = 2000.0;
  EXPECT_THROW(MassSpringModel(flat_grid(5, 5), m), std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
