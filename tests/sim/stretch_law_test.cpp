// Nonlinear stretch laws (sim/material/stretch_law.h), the springs that stretch by them, and the
// measured curves of Wang et al. 2011 (sim/material/wang2011_fabrics.h): each law's tension is
// the derivative of its energy and its stiffness the derivative of its tension (central
// differences); compression continues the slope at zero; bad laws are refused; the springs'
// forces and exact Hessian against finite differences; a grid stretched uniformly stores
// exactly area × W(ε); the Wang curves pass through the file's samples by ARCSim's rules.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sim/cloth_model.h"
#include "sim/mass_spring.h"
#include "sim/material/material.h"
#include "sim/material/material_presets.h"
#include "sim/material/stretch_law.h"
#include "sim/material/wang2011_fabrics.h"
#include "tests/sim/force_term_fd.h"

namespace weft::sim {
namespace {

std::vector<StretchLaw> every_stretch_form() {
  return {StretchLaw::linear(800.0),
          StretchLaw::table({{0.01, 5.0}, {0.05, 40.0}, {0.1, 200.0}, {0.3, 900.0}})};
}

TEST(StretchLaw, TensionIsTheEnergySlopeAndStiffnessTheTensionSlope) {
  for (const StretchLaw& law : every_stretch_form()) {
    for (const double e : {-0.05, -0.001, 0.002, 0.02, 0.07, 0.2, 0.5}) {
      const double h = 1e-7;
      const double dW = (law.energy_density(e + h) - law.energy_density(e - h)) / (2 * h);
      const double dT = (law.tension(e + h) - law.tension(e - h)) / (2 * h);
      EXPECT_NEAR(law.tension(e), dW, 1e-6 * std::max(1.0, std::abs(dW))) << law.describe() << " at " << e;
      EXPECT_NEAR(law.stiffness(e), dT, 1e-5 * std::max(1.0, std::abs(dT))) << law.describe() << " at " << e;
      EXPECT_GT(law.stiffness(e), 0.0);
    }
    EXPECT_EQ(law.tension(0.0), 0.0);
    EXPECT_EQ(law.energy_density(0.0), 0.0);
  }
}

TEST(StretchLaw, CompressionContinuesTheSlopeAtZero) {
  const StretchLaw law = StretchLaw::table({{0.01, 5.0}, {0.05, 40.0}});
  EXPECT_DOUBLE_EQ(law.initial_stiffness(), 500.0);  // the first segment's mean slope
  EXPECT_DOUBLE_EQ(law.tension(-0.02), -10.0);
  EXPECT_DOUBLE_EQ(law.energy_density(-0.02), 0.5 * 500.0 * 0.02 * 0.02);
  EXPECT_DOUBLE_EQ(law.tension(0.05), 40.0);
  EXPECT_DOUBLE_EQ(law.tension(0.15), 40.0 + 875.0 * 0.1);  // beyond: the last mean slope
}

TEST(StretchLaw, TakingOffTheDiagonalsLeavesTheRestAndRefusesWhatWouldNotRise) {
  const StretchLaw law = StretchLaw::table({{0.01, 5.0}, {0.05, 40.0}});
  const StretchLaw edge = law.minus_linear(100.0);
  for (const double e : {-0.01, 0.005, 0.03, 0.2})
    EXPECT_NEAR(edge.tension(e), law.tension(e) - 100.0 * e, 1e-12);
  EXPECT_THROW((void)law.minus_linear(600.0), MaterialError);
  EXPECT_THROW((void)StretchLaw::linear(300.0).minus_linear(300.0), MaterialError);
}

TEST(StretchLaw, RefusesLawsWithoutAStableShape) {
  EXPECT_THROW(StretchLaw::linear(0.0), MaterialError);
  EXPECT_THROW(StretchLaw::linear(INFINITY), MaterialError);
  EXPECT_THROW(StretchLaw::table({}), MaterialError);
  EXPECT_THROW(StretchLaw::table({{0.1, 5.0}, {0.05, 6.0}}), MaterialError);  // ε not rising
  EXPECT_THROW(StretchLaw::table({{0.1, 5.0}, {0.2, 5.0}}), MaterialError);   // T not rising
  try {
    StretchLaw::table({{0.01, 1.0}, {0.02, NAN}});
    FAIL();
  } catch (const MaterialError& e) {
    EXPECT_NE(std::string(e.what()).find("stretch law: table point 2 (0.02, nan N/m)"), std::string::npos)
        << e.what();
  }
}

// The spring term of a 5 × 4 sheet whose warp and weft both stretch by laws, stretched by
// different amounts along each and perturbed: the forces are minus the energy's gradient and the
// assembled exact Hessian the forces' derivative; the projected one is PSD.
TEST(StretchLawSprings, ForcesAndExactStiffnessMatchFiniteDifferences) {
  const ClothMesh mesh = fd::flat_sheet(5, 4, 0.04, 0.03);
  Material m = fd::anisotropic_fabric();
  m.stretch_law_warp = StretchLaw::table({{0.01, 12.0}, {0.05, 90.0}, {0.2, 900.0}});
  m.stretch_law_weft = StretchLaw::table({{0.02, 4.0}, {0.1, 300.0}});
  m.stretch_warp_N_m = m.stretch_law_warp->initial_stiffness();
  m.stretch_weft_N_m = m.stretch_law_weft->initial_stiffness();
  m.bend_warp_Nm = m.bend_weft_Nm = 0.0;
  const ForceTerms terms = MassSpringModel(mesh, m).terms();
  ASSERT_EQ(terms.size(), 1u);
  for (const double stretch : {0.0, 0.03, 0.12}) {
    SCOPED_TRACE("stretch " + std::to_string(stretch));
    Matrix3X x = mesh.rest_positions;
    x.col(0) *= 1.0 + stretch;
    x.col(1) *= 1.0 + 0.5 * stretch;
    x = fd::perturbed(x, 2e-4, 7);
    fd::expect_forces_match_energy(*terms[0], x, 1e-8, 1e-5);
    fd::expect_assembled_stiffness_matches_forces(*terms[0], x, 1e-8, 2e-4);
    fd::expect_positive_semidefinite(fd::assembled_stiffness(*terms[0], x, /*project_psd=*/true));
  }
}

// With no shear (no diagonals), a grid stretched uniformly by ε along the weft holds exactly
// the law's energy per area over its area, W(ε) · A, and none along the warp: the springs'
// tributary widths tile the sheet.
TEST(StretchLawSprings, AUniformStretchStoresTheLawsEnergyOverTheArea) {
  const ClothMesh mesh = fd::flat_sheet(7, 9, 0.06, 0.08);
  const Wang2011Fabric& sweater = wang2011_fabrics()[4];
  ASSERT_EQ(sweater.file, "navy-sparkle-sweat");
  Material m;
  m.stretch_law_weft = wang2011_stretch_law(sweater, FabricAxis::v);
  m.stretch_weft_N_m = m.stretch_law_weft->initial_stiffness();
  m.shear_N_m = m.bend_warp_Nm = m.bend_weft_Nm = 0.0;
  const MassSpringModel model(mesh, m);
  for (const double e : {-0.01, 0.004, 0.05, 0.16, 0.3}) {
    Matrix3X x = mesh.rest_positions;
    x.col(1) *= 1.0 + e;
    EXPECT_NEAR(model.energy(x), 0.06 * 0.08 * m.stretch_law_weft->energy_density(e),
                1e-12 + 1e-12 * model.energy(x))
        << "strain " << e;
  }
}

// ARCSim's rules on the file's numbers (hand-computed): the 11 oz denim's weft-wise (v) curve at
// the 7/6-stretch sample, λ k (λ² − 1)/2 with k = 2 × row 5's c22; its moment along u at 10 m⁻¹,
// (ke/4) κ from row 2, column 1 (assets/fabrics/README.md: 2.70e-4 N).
TEST(Wang2011Curves, PassThroughTheFilesSamplesByArcsimsRules) {
  const Wang2011Fabric& denim = wang2011_fabrics()[0];
  ASSERT_EQ(denim.file, "11oz-black-denim");
  const double lambda = 7.0 / 6.0;
  EXPECT_NEAR(wang2011_stretch_law(denim, FabricAxis::v).tension(1.0 / 6.0),
              lambda * 2.0 * 1051.55712 * 0.5 * (lambda * lambda - 1.0), 1e-9);
  EXPECT_NEAR(wang2011_bending_law(denim, FabricAxis::u).moment(10.0), 107.848228e-6 / 4.0 * 10.0, 1e-15);
  EXPECT_NEAR(wang2011_bending_law(denim, FabricAxis::v).moment(30.0), 62.433697e-6 / 4.0 * 30.0, 1e-15);
}

// The knits stiffen: the sweater's weft-wise stiffness at 1/6 strain is tens of times its
// stiffness at rest (c22 goes from 3.27 to 243 N/m between the samples), the woven
// tablecloth's barely changes (2027 → 2150).
TEST(Wang2011Curves, KnitsStiffenManyTimesAndWovensBarely) {
  const auto stiffening = [](const Wang2011Fabric& f) {
    const StretchLaw law = wang2011_stretch_law(f, FabricAxis::v);
    return law.stiffness(0.2) / law.initial_stiffness();
  };
  EXPECT_GT(stiffening(wang2011_fabrics()[4]), 50.0);  // navy-sparkle-sweat
  EXPECT_LT(stiffening(wang2011_fabrics()[8]), 2.0);   // white-dots-on-blk
  EXPECT_GT(stiffening(wang2011_fabrics()[8]), 1.0);
}

TEST(StretchLaw, OnlyTheMassSpringGridsStructuralSpringsStretchByALaw) {
  Material m;
  m.stretch_law_warp = StretchLaw::table({{0.01, 12.0}, {0.05, 90.0}});
  m.stretch_warp_N_m = m.stretch_law_warp->initial_stiffness();
  const ClothMesh mesh = fd::flat_sheet(5, 5, 0.1, 0.1);
  EXPECT_NO_THROW(make_force_terms(mesh, m, ClothModel::mass_spring, true));
  EXPECT_THROW(make_force_terms(mesh, m, ClothModel::mass_spring, false), MaterialError);
  EXPECT_THROW(make_force_terms(mesh, m, ClothModel::baraff_witkin, true), MaterialError);
  EXPECT_THROW(make_force_terms(mesh, m, ClothModel::rft6, true), MaterialError);
}

}  // namespace
}  // namespace weft::sim
