// Folds of a hanging curtain down its centre column (analysis/measure/curtain_folds.h): the zigzag
// count on sequences whose extremes are known, and on curtains — flat (none), and laid onto
// seed 001's tension-field folds, whose n wrinkles have n + 1 lines.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "base/constants.h"
#include "sim/folds/fold_geometry.h"
#include "sim/folds/tension_field.h"
#include "sim/grid.h"
#include "analysis/measure/curtain_folds.h"

namespace weft::analysis {
namespace {

std::vector<double> sampled(int samples, const std::function<double(double)>& f) {
  std::vector<double> v;
  for (int k = 0; k < samples; ++k) v.push_back(f(double(k) / (samples - 1)));
  return v;
}

TEST(CurtainFolds, ZigzagCountsEachExtremeOfASineOnce) {
  // sin over m half periods from a zero: m interior extremes, plus both ends when they are
  // farther than the hysteresis from the neighbouring extremes (they are: at 0).
  for (int m = 1; m <= 9; ++m) {
    const auto v = sampled(401, [&](double s) { return std::sin(m * base::kPi * s); });
    EXPECT_EQ(count_alternating_extremes(v, 0.2), m + 2) << m << " half periods";
  }
  // From a crest: the start is an extreme, the ends at 0 … the count is the same rule.
  const auto cos3 = sampled(401, [](double s) { return std::cos(3 * base::kPi * s); });
  EXPECT_EQ(count_alternating_extremes(cos3, 0.2), 4);
}

TEST(CurtainFolds, WigglesBelowTheHysteresisDoNotCount) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.04, 0.04);
  const auto v = sampled(401, [&](double s) { return std::sin(4 * base::kPi * s) + noise(rng); });
  EXPECT_EQ(count_alternating_extremes(v, 0.2), 6);
  EXPECT_EQ(count_alternating_extremes(std::vector<double>(50, 1.0), 0.2), 0);
  EXPECT_EQ(count_alternating_extremes({}, 0.2), 0);
  EXPECT_THROW(count_alternating_extremes(v, 0.0), std::invalid_argument);
}

sim::GridSpec curtain_grid(double width_m, double height_m, sim::Index n) {
  sim::GridSpec g;
  g.size_u_m = width_m;
  g.size_v_m = height_m;
  g.nu = g.nv = n;
  g.origin = sim::Vec3(-0.5 * width_m, 0.0, 1.6);
  g.warp_axis = sim::Vec3(1, 0, 0);
  g.weft_axis = sim::Vec3(0, 0, -1);
  return g;
}

TEST(CurtainFolds, AFlatCurtainHasNone) {
  const sim::ClothMesh mesh = sim::make_grid(curtain_grid(1.4, 1.4, 31));
  EXPECT_EQ(count_curtain_folds(mesh, mesh.rest_positions).folds, 0);
}

TEST(CurtainFolds, TheTensionFieldShapeHasOneBulgePerWrinkleLine) {
  // Seed 001 Table 1 (L = 140 cm, d = 10 cm, t = 0.25 mm, E = 165 MPa, w = 15e-7 N/mm²) with
  // the paper's Q: n = 5, 7, 8 wrinkles for h = 90, 140, 235 cm.
  const double heights[] = {0.90, 1.40, 2.35}, ratios[] = {1.31, 1.29, 1.34};
  for (int k = 0; k < 3; ++k) {
    sim::TensionFieldInputs in;
    in.height_m = heights[k];
    in.width_m = 1.40;
    in.support_shift_m = 0.10;
    in.thickness_m = 0.25e-3;
    in.youngs_modulus_Pa = 165e6;
    in.weight_N_m2 = 1.5;
    in.ratio = ratios[k];
    const sim::TensionFieldResult r = sim::solve_tension_field(in);
    const sim::FoldPattern pattern = sim::make_fold_pattern(in, r);
    const sim::ClothMesh mesh = sim::make_grid(curtain_grid(in.width_m, in.height_m, 141));
    const sim::Matrix3X x =
        sim::fold_rest_positions(pattern, mesh.rest_positions, sim::Vec3(0.0, 0.0, 1.6));
    EXPECT_EQ(count_curtain_folds(mesh, x).folds, r.wrinkles + 1) << "h = " << heights[k];
  }
}

}  // namespace
}  // namespace weft::analysis
