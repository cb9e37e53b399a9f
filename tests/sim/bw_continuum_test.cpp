// The Baraff–Witkin continuum terms (sim/continuum/): derivatives against finite differences,
// rigid-motion invariance, and patch tests against the continuum energies they discretize.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/cloth_model.h"
#include "sim/continuum/bw_membrane.h"
#include "sim/continuum/hinge_bending.h"
#include "tests/sim/cylinder_bend.h"
#include "tests/sim/force_term_fd.h"

namespace weft::sim {
namespace {

using fd::expect_assembled_stiffness_matches_forces;
using fd::expect_forces_match_energy;
using fd::perturbed;

Material test_material() {
  return fd::anisotropic_fabric();
}

ClothMesh small_sheet(Index nu = 4, Index nv = 3, double size_u = 0.3, double size_v = 0.2) {
  return fd::flat_sheet(nu, nv, size_u, size_v);
}

Matrix3X rotated(const Matrix3X& x, const Eigen::Matrix3d& R, const Vec3& t) {
  Matrix3X y = x;
  for (Eigen::Index i = 0; i < x.rows(); ++i) y.row(i) = (R * x.row(i).transpose() + t).transpose();
  return y;
}

Eigen::Matrix3d some_rotation() {
  return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) *
          Eigen::AngleAxisd(-1.9, Vec3::UnitZ()))
      .toRotationMatrix();
}

TEST(BwMembrane, ForcesAreMinusTheEnergyGradient) {
  const ClothMesh mesh = small_sheet();
  const BwMembrane term(mesh, test_material(), true);
  for (unsigned seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    // Up to 30 % of a cell: stretch, compression and large shear all occur.
    expect_forces_match_energy(term, perturbed(mesh.rest_positions, 0.03, seed));
  }
}

TEST(BwMembrane, ExactStiffnessMatchesFiniteDifferences) {
  const ClothMesh mesh = small_sheet(3, 3);
  const BwMembrane term(mesh, test_material(), true);
  for (unsigned seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE(seed);
    expect_assembled_stiffness_matches_forces(term, perturbed(mesh.rest_positions, 0.03, seed));
  }
}

TEST(BwMembrane, ProjectedStiffnessIsPositiveSemidefiniteAndExactAtRest) {
  const ClothMesh mesh = small_sheet(3, 3);
  const BwMembrane term(mesh, test_material(), true);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Matrix3X x = perturbed(mesh.rest_positions, 0.05, seed);
    SCOPED_TRACE(seed);
    fd::expect_positive_semidefinite(fd::assembled_stiffness(term, x, true));
  }
  const Matrix3X rest = rotated(mesh.rest_positions, some_rotation(), Vec3(0.1, -2, 3));
  const Eigen::MatrixXd projected = fd::assembled_stiffness(term, rest, true);
  const Eigen::MatrixXd exact = fd::assembled_stiffness(term, rest, false);
  EXPECT_LE((projected - exact).cwiseAbs().maxCoeff(), 1e-9 * exact.cwiseAbs().maxCoeff());
}

TEST(BwMembrane, RigidMotionsCostNothing) {
  const ClothMesh mesh = small_sheet();
  const BwMembrane term(mesh, test_material(), true);
  const Matrix3X x = rotated(mesh.rest_positions, some_rotation(), Vec3(0.3, 0.2, -1.0));
  EXPECT_NEAR(term.energy(x), 0.0, 1e-20);
  Matrix3X f = Matrix3X::Zero(x.rows(), 3);
  term.add_forces(x, f);
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-10);
}

// Uniform stretch ε along warp or weft: E = ½ Y ε² A, the continuum energy, on any mesh.
TEST(BwMembrane, UniformStretchGivesTheContinuumEnergy) {
  const ClothMesh mesh = small_sheet();
  const Material m = test_material();
  const BwMembrane term(mesh, m, true);
  const double area = 0.3 * 0.2, eps = 0.02;
  Matrix3X x = mesh.rest_positions;
  x.col(0) *= 1.0 + eps;  // the grid's warp axis is x
  EXPECT_NEAR(term.energy(x), 0.5 * m.stretch_warp_N_m * eps * eps * area, 1e-12);
  x = mesh.rest_positions;
  x.col(1) *= 1.0 + eps;
  EXPECT_NEAR(term.energy(x), 0.5 * m.stretch_weft_N_m * eps * eps * area, 1e-12);
}

// Pure shear by an angle γ (weft threads turned by γ, lengths kept): E = ½ G γ² A, exactly,
// also at a large angle where Baraff–Witkin's w_u·w_v = sin γ would understate it.
TEST(BwMembrane, PureShearGivesTheContinuumEnergy) {
  const ClothMesh mesh = small_sheet();
  const Material m = test_material();
  const BwMembrane term(mesh, m, true);
  const double area = 0.3 * 0.2;
  for (double gamma : {0.01, 0.5}) {
    Matrix3X x = mesh.rest_positions;
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      const Vec2 uv = mesh.material_coords[static_cast<std::size_t>(i)];
      x(i, 0) = uv.x() + uv.y() * std::sin(gamma);
      x(i, 1) = uv.y() * std::cos(gamma);
    }
    EXPECT_NEAR(term.energy(x) / (0.5 * m.shear_N_m * gamma * gamma * area), 1.0, 1e-9) << gamma;
  }
}

TEST(HingeBending, ForcesAreMinusTheEnergyGradient) {
  const ClothMesh mesh = small_sheet();
  const HingeBending term(mesh, test_material());
  for (unsigned seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    expect_forces_match_energy(term, perturbed(mesh.rest_positions, 0.02, seed), 1e-7, 1e-5);
  }
}

// The stiffness is Gauss–Newton k ∇θ∇θᵀ (hinge_kernel.h): exact where every hinge is at its
// rest angle — on the flat sheet, rigidly moved — and PSD everywhere.
TEST(HingeBending, StiffnessIsExactAtRestAndPositiveSemidefinite) {
  const ClothMesh mesh = small_sheet(3, 3);
  const HingeBending term(mesh, test_material());
  expect_assembled_stiffness_matches_forces(
      term, rotated(mesh.rest_positions, some_rotation(), Vec3(1, 2, 3)), 1e-6, 1e-4);
  fd::expect_positive_semidefinite(
      fd::assembled_stiffness(term, perturbed(mesh.rest_positions, 0.02, 7), true));
}

// A sheet rolled onto a cylinder of curvature κ along the warp (or the weft) stores
// ½ B κ² per area with B the warp (or weft) rigidity. On the grid only the hinges across the
// bending direction fold, each by exactly κ h (the chords' turning angle), and the outermost
// half cells on either side carry none: E = ½ B κ² (L − h) W. The relative shortfall h / L
// vanishes under refinement.
TEST(HingeBending, CylinderGivesTheContinuumEnergyPerArea) {
  const Material m = test_material();
  const double L = 0.3, W = 0.2, kappa = 5.0;
  for (bool along_warp : {true, false}) {
    double previous_error = 1.0;
    for (Index n : {7, 13, 25}) {
      const ClothMesh mesh = small_sheet(n, n, L, W);
      const HingeBending term(mesh, m);
      const Matrix3X x = test::bent_into_cylinder(mesh, kappa, along_warp);
      const double B = along_warp ? m.bend_warp_Nm : m.bend_weft_Nm;
      const double length = along_warp ? L : W, width = along_warp ? W : L;
      const double h = length / static_cast<double>(n - 1);
      EXPECT_NEAR(term.energy(x) / (0.5 * B * kappa * kappa * (length - h) * width), 1.0, 1e-9)
          << (along_warp ? "warp" : "weft") << " n " << n;
      const double error =
          std::abs(term.energy(x) / (0.5 * B * kappa * kappa * length * width) - 1.0);
      EXPECT_LT(error, previous_error);
      previous_error = error;
    }
  }
}

TEST(ClothModel, BuildsOnlyTheTermsTheMaterialNeeds) {
  const ClothMesh mesh = small_sheet();
  Material m = test_material();
  EXPECT_EQ(make_force_terms(mesh, m, ClothModel::baraff_witkin, true).size(), 2u);
  // The mass-spring model is force terms too: springs, then angular bending.
  EXPECT_EQ(make_force_terms(mesh, m, ClothModel::mass_spring, true).size(), 2u);
  m.bend_warp_Nm = m.bend_weft_Nm = 0.0;
  EXPECT_EQ(make_force_terms(mesh, m, ClothModel::mass_spring, true).size(), 1u);
  const ForceTerms terms = make_force_terms(mesh, m, ClothModel::baraff_witkin, true);
  ASSERT_EQ(terms.size(), 1u);
  EXPECT_NE(terms[0]->describe().find("stretch and shear"), std::string::npos);
  m.shear_N_m = 0.0;
  EXPECT_TRUE(make_force_terms(mesh, m, ClothModel::baraff_witkin, false).empty());
}

}  // namespace
}  // namespace weft::sim
