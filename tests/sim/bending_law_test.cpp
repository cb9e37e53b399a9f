// Nonlinear bending laws (sim/material/bending_law.h) and the angular bending term that bends by them:
// each law's moment is the derivative of its energy and its stiffness the derivative of its
// moment (central differences), the table passes through its points, bad laws are refused;
// the angular term's forces and exact Hessian against finite differences, linear and nonlinear,
// bent and nearly flat; its PSD projection.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim/material/bending_law.h"
#include "sim/cloth_model.h"
#include "sim/mass_spring.h"
#include "sim/material/material.h"
#include "tests/sim/force_term_fd.h"

namespace weft::sim {
namespace {

std::vector<BendingLaw> every_form() {
  return {BendingLaw::linear(0.05), BendingLaw::frictional(0.009, 0.22, 0.45),
          BendingLaw::cubic(0.05, 2e-4),
          BendingLaw::table({{0.4, 0.19}, {2.0, 0.26}, {12.0, 0.34}, {20.0, 0.39}})};
}

TEST(BendingLaw, MomentIsTheEnergySlopeAndStiffnessTheMomentSlope) {
  for (const BendingLaw& law : every_form()) {
    for (const double kappa : {-15.0, -1.1, -0.1, 0.05, 0.3, 1.0, 7.0, 16.0, 30.0}) {
      const double h = 1e-6 * std::max(1.0, std::abs(kappa));
      const double dW = (law.energy_density(kappa + h) - law.energy_density(kappa - h)) / (2 * h);
      const double dM = (law.moment(kappa + h) - law.moment(kappa - h)) / (2 * h);
      EXPECT_NEAR(law.moment(kappa), dW, 1e-7 * std::max(1.0, std::abs(dW))) << law.describe() << " at " << kappa;
      EXPECT_NEAR(law.stiffness(kappa), dM, 1e-6 * std::max(1.0, std::abs(dM))) << law.describe() << " at " << kappa;
      EXPECT_GT(law.stiffness(kappa), 0.0);
      EXPECT_DOUBLE_EQ(law.moment(-kappa), -law.moment(kappa));
      EXPECT_DOUBLE_EQ(law.energy_density(-kappa), law.energy_density(kappa));
    }
    EXPECT_EQ(law.moment(0.0), 0.0);
    EXPECT_EQ(law.energy_density(0.0), 0.0);
  }
}

TEST(BendingLaw, FrictionalLawIsStiffAtFirstAndItsSlopeBeyond) {
  const BendingLaw law = BendingLaw::frictional(0.01, 0.2, 0.5);
  EXPECT_DOUBLE_EQ(law.initial_rigidity(), 0.01 + 0.2 / 0.5);
  EXPECT_NEAR(law.moment(50.0), 0.01 * 50.0 + 0.2, 1e-12);  // tanh(100) = 1
  EXPECT_NEAR(law.stiffness(50.0), 0.01, 1e-12);
}

TEST(BendingLaw, TablePassesThroughItsPointsAndExtendsItsLastSlope) {
  const BendingLaw law = BendingLaw::table({{1.0, 0.5}, {3.0, 0.7}});
  EXPECT_DOUBLE_EQ(law.moment(1.0), 0.5);
  EXPECT_DOUBLE_EQ(law.moment(3.0), 0.7);
  EXPECT_DOUBLE_EQ(law.moment(5.0), 0.9);                       // the last segment's mean slope
  EXPECT_DOUBLE_EQ(law.initial_rigidity(), 0.5);                // the first segment's
  // The interior point's slope is the weighted harmonic mean of its segments' (h = 1, 2):
  // (w1 + w2) / (w1/0.5 + w2/0.1) with w1 = 2·2 + 1, w2 = 2 + 2·1.
  const double d1_first = 9.0 / (5.0 / 0.5 + 4.0 / 0.1);
  EXPECT_NEAR(law.stiffness(1.0), d1_first, 1e-15);
  // Concave data (mean slopes 0.5, then 0.1) give a curve above the chord in the first segment,
  // and the energy is its integral: the trapezoid rule plus h² (d0 − d1)/12 for a Hermite cubic.
  EXPECT_NEAR(law.moment(0.5), 0.5 * 0.125 + 0.5 * 0.5 - d1_first * 0.125, 1e-15);
  EXPECT_NEAR(law.energy_density(1.0), 0.5 * 0.5 + (0.5 - d1_first) / 12.0, 1e-15);
}

TEST(BendingLaw, TableStiffnessIsContinuousAndPositive) {
  const BendingLaw law = BendingLaw::table({{0.4, 0.19}, {2.0, 0.26}, {12.0, 0.34}, {20.0, 0.39}});
  for (const double kappa : {0.0, 0.4, 2.0, 12.0, 20.0}) {
    const double h = 1e-9;
    EXPECT_NEAR(law.stiffness(kappa + h), law.stiffness(std::max(0.0, kappa - h)), 1e-6 * law.stiffness(kappa))
        << "at " << kappa;
  }
  for (double kappa = 0.0; kappa < 25.0; kappa += 0.01) EXPECT_GT(law.stiffness(kappa), 0.0);
}

TEST(BendingLaw, RefusesLawsWithoutAStableShape) {
  EXPECT_THROW(BendingLaw::linear(0.0), MaterialError);
  EXPECT_THROW(BendingLaw::frictional(0.01, -0.1, 1.0), MaterialError);
  EXPECT_THROW(BendingLaw::frictional(0.01, 0.1, 0.0), MaterialError);
  EXPECT_THROW(BendingLaw::cubic(0.01, -1.0), MaterialError);
  EXPECT_THROW(BendingLaw::table({}), MaterialError);
  EXPECT_THROW(BendingLaw::table({{1.0, 0.5}, {0.5, 0.6}}), MaterialError);  // κ not rising
  EXPECT_THROW(BendingLaw::table({{1.0, 0.5}, {2.0, 0.5}}), MaterialError);  // M not rising
  EXPECT_THROW(BendingLaw::table({{1.0, NAN}}), MaterialError);
  try {
    BendingLaw::table({{1.0, 0.5}, {2.0, 0.4}});
    FAIL();
  } catch (const MaterialError& e) {
    EXPECT_NE(std::string(e.what()).find("table point 2"), std::string::npos) << e.what();
  }
}

// The angular term of a 6 × 4 sheet, bent into an arch along both directions and perturbed.
Matrix3X bent_sheet(const ClothMesh& mesh, double amount, unsigned seed) {
  Matrix3X x = mesh.rest_positions;
  for (Index i = 0; i < x.rows(); ++i) x(i, 2) += amount * (x(i, 0) * x(i, 0) - 0.5 * x(i, 1) * x(i, 1));
  return fd::perturbed(x, 1e-3, seed);
}

std::shared_ptr<const ForceTerm> angular_term(const ClothMesh& mesh, const Material& m) {
  for (const auto& term : MassSpringModel(mesh, m).terms())
    if (dynamic_cast<const AngularBendingTerm*>(term.get())) return term;
  return nullptr;
}

TEST(AngularBending, ForcesAndExactStiffnessMatchFiniteDifferencesForEveryLaw) {
  const ClothMesh mesh = fd::flat_sheet(6, 4, 0.05, 0.03);
  for (const BendingLaw& law : every_form()) {
    Material m = fd::anisotropic_fabric();
    m.bend_law_warp = law;
    m.bend_warp_Nm = law.initial_rigidity();
    const auto term = angular_term(mesh, m);
    ASSERT_TRUE(term);
    EXPECT_TRUE(term->has_stiffness());
    for (const double amount : {0.0, 4.0, 25.0}) {
      SCOPED_TRACE(law.describe() + ", arch " + std::to_string(amount));
      const Matrix3X x = bent_sheet(mesh, amount, 3);
      fd::expect_forces_match_energy(*term, x, 1e-7, 1e-5);
      fd::expect_assembled_stiffness_matches_forces(*term, x, 1e-6, 2e-4);
      fd::expect_positive_semidefinite(fd::assembled_stiffness(*term, x, /*project_psd=*/true));
    }
  }
}

TEST(AngularBending, FlatStiffnessIsTheSmallAngleLimit) {
  // Exactly flat: the stiffness of E = ½ k θ² is k [1 −2 1]ᵀ[1 −2 1] / l² across the line.
  const double k = 2e-4, l = 0.01;
  AngularBendingTerm term({{0, 1, 2, 0.0, k, l}});
  Matrix3X x(3, 3);
  x << 0, 0, 0, l, 0, 0, 2 * l, 0, 0;
  ElementMatrix K;
  term.element_stiffness(x, 0, K, false);
  const Eigen::Vector3d w(1, -2, 1);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(K(3 * a + 2, 3 * b + 2), k * w[a] * w[b] / (l * l), 1e-9 * k / (l * l));
      EXPECT_NEAR(K(3 * a + 1, 3 * b + 1), k * w[a] * w[b] / (l * l), 1e-9 * k / (l * l));
      EXPECT_NEAR(K(3 * a, 3 * b), 0.0, 1e-12 * k / (l * l));  // along the line: no bending
    }
}

TEST(AngularBending, TimeStepStiffnessIsTheExactHessianOfAStraightStencilInAnyDirection) {
  const double k = 2e-4, l = 0.01;
  AngularBendingTerm term({{0, 1, 2, 0.0, k, l}});
  const Vec3 t = Vec3(0.3, -0.5, 0.8).normalized();
  Matrix3X x(3, 3);
  for (int i = 0; i < 3; ++i) x.row(i) = (Vec3(0.2, 0.1, -0.4) + i * l * t).transpose();
  ElementMatrix exact, step;
  term.element_stiffness(x, 0, exact, false);
  term.time_step_stiffness(x, 0, step);
  ASSERT_EQ(step.rows(), 9);
  EXPECT_LT((step - exact).cwiseAbs().maxCoeff(), 1e-9 * k / (l * l));
}

TEST(AngularBending, TimeStepStiffnessOfABentStencilIsPsdAndIgnoresRigidAndChordMotion) {
  Material m = fd::anisotropic_fabric();
  m.bend_law_warp = BendingLaw::frictional(0.009, 0.22, 0.45);
  m.bend_warp_Nm = m.bend_law_warp->initial_rigidity();
  const ClothMesh mesh = fd::flat_sheet(6, 4, 0.05, 0.03);
  const auto term = angular_term(mesh, m);
  ASSERT_TRUE(term);
  const Matrix3X x = bent_sheet(mesh, 25.0, 5);
  Index stencil[kMaxStencil];
  ElementMatrix K;
  for (std::size_t e = 0; e < term->element_count(); ++e) {
    term->stencil(e, stencil);
    term->time_step_stiffness(x, e, K);
    fd::expect_positive_semidefinite(K);
    const Vec3 chord = vertex(x, stencil[2]) - vertex(x, stencil[0]);
    Eigen::Matrix<double, 9, 1> shift, along;  // a rigid translation; the ends along the chord
    shift << 1, -2, 3, 1, -2, 3, 1, -2, 3;
    along << -chord, Vec3::Zero(), chord;
    EXPECT_LT((K * shift).norm(), 1e-9 * K.norm() * shift.norm());
    EXPECT_LT((K * along).norm(), 1e-9 * K.norm() * along.norm());
  }
}

TEST(BendingLaw, OnlyTheMassSpringGridBendsByALaw) {
  Material m;
  m.bend_law_weft = BendingLaw::cubic(m.bend_weft_Nm, 1e-6);
  const ClothMesh mesh = fd::flat_sheet(5, 5, 0.1, 0.1);
  EXPECT_NO_THROW(make_force_terms(mesh, m, ClothModel::mass_spring, true));
  EXPECT_THROW(make_force_terms(mesh, m, ClothModel::baraff_witkin, true), MaterialError);
  EXPECT_THROW(make_force_terms(mesh, m, ClothModel::rft3, true), MaterialError);
}

}  // namespace
}  // namespace weft::sim
