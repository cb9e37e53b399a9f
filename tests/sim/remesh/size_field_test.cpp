// Target size field of seed 002 eq. 29 and the remeshing indicator (sim/remesh/size_field.h).

#include "sim/remesh/size_field.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/remesh/curvature.h"
#include "tests/sim/remesh/test_meshes.h"

namespace weft::sim::remesh {
namespace {

TEST(SizeField, FollowsEquation29BetweenItsBounds) {
  const SizeFieldParams p{/*c_m=*/1e-3, /*h_min_m=*/0.004, /*h_max_m=*/0.04};
  // |κ| h² = c wherever the bounds do not act: |κ| from c/h_max² = 0.625 to c/h_min² = 62.5.
  for (double kappa : {0.7, 1.0, 5.0, 20.0, 60.0}) {
    const double h = target_size(kappa, p);
    EXPECT_NEAR(kappa * h * h, p.c_m, 1e-15) << "kappa " << kappa;
    EXPECT_DOUBLE_EQ(h, std::sqrt(p.c_m / kappa));
  }
}

TEST(SizeField, ClampsAtHminAndHmax) {
  const SizeFieldParams p{1e-3, 0.004, 0.04};
  EXPECT_EQ(target_size(0.0, p), p.h_max_m);    // flat cloth
  EXPECT_EQ(target_size(0.5, p), p.h_max_m);    // √(c/κ) = 0.0447 > h_max
  EXPECT_EQ(target_size(100.0, p), p.h_min_m);  // √(c/κ) = 0.00316 < h_min
  EXPECT_EQ(target_size(1e12, p), p.h_min_m);
  const Eigen::VectorXd h = target_sizes(Eigen::Vector3d(0.0, 2.5, 1e3), p);
  EXPECT_EQ(h(0), 0.04);
  EXPECT_DOUBLE_EQ(h(1), 0.02);
  EXPECT_EQ(h(2), 0.004);
}

TEST(SizeField, BadParametersAreErrorsNamingThem) {
  const auto message = [](SizeFieldParams p) {
    try {
      check_size_field_params(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({0.0, 0.01, 0.1}).find("c ="), std::string::npos);
  EXPECT_NE(message({1e-3, -0.01, 0.1}).find("h_min"), std::string::npos);
  EXPECT_NE(message({1e-3, 0.01, 0.005}).find("h_max"), std::string::npos);
  EXPECT_NE(message({1e-3, 0.01, NAN}).find("h_max"), std::string::npos);
  EXPECT_EQ(message({1e-3, 0.01, 0.01}), "");
}

TEST(SizeField, IndicatorIsCurvatureTimesSizeSquaredOnACylinder) {
  // Uniform cells of 1 cm on a cylinder of radius 10 cm: triangle h = (2 + √2)/3 cm, so the
  // indicator is h²/R.
  const double R = 0.1, cell = 0.01;
  const auto m = testing::grid_mesh(0.2, 0.2, 21, 21);
  const Matrix3X x = testing::deform(
      m.material, [&](double u, double v) { return testing::on_cylinder(u, v, R); });
  const Eigen::VectorXd kappa = Eigen::VectorXd::Constant(m.material.rows(), 1.0 / R);
  const double h = cell * (2.0 + std::sqrt(2.0)) / 3.0;
  SizeFieldParams p{1e-3, 0.001, 0.1};
  EXPECT_NEAR(remesh_indicator(m.material, m.triangles, kappa, p), h * h / R, 1e-15);
  // With the estimated curvature: the same within the estimate's error (boundary included).
  EXPECT_NEAR(
      remesh_indicator(m.material, m.triangles, vertex_curvature(m.material, m.triangles, x), p),
      h * h / R, 0.05 * h * h / R);
  // Triangles already at h_min cannot be refined: they do not call for a remesh.
  p.h_min_m = 0.02;
  EXPECT_EQ(remesh_indicator(m.material, m.triangles, kappa, p), 0.0);
  // A fold sharper than h_min resolves counts as the curvature at which eq. 29 reaches h_min,
  // c/h_min²: for h_min = h/2, at most 4 c, whatever |κ|.
  p.h_min_m = 0.5 * h;
  const Eigen::VectorXd sharp = Eigen::VectorXd::Constant(m.material.rows(), 1e4);
  EXPECT_NEAR(remesh_indicator(m.material, m.triangles, sharp, p), 4.0 * p.c_m, 1e-15);
}

// The coarsening criterion counts triangles against what eq. 29 asks for: on uniform cells
// of 1 cm (triangle h = (2 + √2)/3 cm) it is (h_target/h)², with h_target = h_max for a flat
// cloth and √(c/|κ|) on a cylinder; half the sheet flat, half curved: the area-weighted ratio.
TEST(SizeField, RefinementExcessIsTheRatioOfTriangleCounts) {
  const auto m = testing::grid_mesh(0.2, 0.2, 21, 21);
  const double h = 0.01 * (2.0 + std::sqrt(2.0)) / 3.0;
  const SizeFieldParams p{1e-3, 0.002, 0.05};
  const Eigen::VectorXd flat = Eigen::VectorXd::Zero(m.material.rows());
  EXPECT_NEAR(refinement_excess(m.material, m.triangles, flat, p), std::pow(0.05 / h, 2), 1e-12);
  const Eigen::VectorXd cylinder = Eigen::VectorXd::Constant(m.material.rows(), 4.0);
  const double h_target = std::sqrt(1e-3 / 4.0);  // 1.58 cm
  EXPECT_NEAR(refinement_excess(m.material, m.triangles, cylinder, p), std::pow(h_target / h, 2),
              1e-12);
  // Curved where u < 10 cm (the triangles whose three corners are there), flat elsewhere: the
  // current mesh's count over the target's, Σ A/h² / (A_curved/h_target² + A_flat/h_max²).
  Eigen::VectorXd half = flat;
  for (Index k = 0; k < m.material.rows(); ++k)
    if (m.material(k, 0) < 0.1 - 1e-12) half(k) = 4.0;
  double curved_area = 0.0, total_area = 0.0;
  for (Index t = 0; t < m.triangles.rows(); ++t) {
    const double area = 0.5 * 0.01 * 0.01;
    total_area += area;
    // A triangle straddling u = 10 cm has a mean |κ| of 4/3 or 8/3: eq. 29 of that.
    int curved = 0;
    for (int c = 0; c < 3; ++c) curved += half(m.triangles(t, c)) > 0.0;
    const double ht = target_size(4.0 * curved / 3.0, p);
    curved_area += area * (1.0 / (ht * ht) - 1.0 / (0.05 * 0.05));
  }
  const double expected = (total_area / (h * h)) / (total_area / (0.05 * 0.05) + curved_area);
  EXPECT_NEAR(refinement_excess(m.material, m.triangles, half, p), expected, 1e-12 * expected);
  // A finer mesh of the same flat sheet has 4× the excess.
  const auto fine = testing::grid_mesh(0.2, 0.2, 41, 41);
  EXPECT_NEAR(refinement_excess(fine.material, fine.triangles,
                                Eigen::VectorXd::Zero(fine.material.rows()), p),
              4.0 * std::pow(0.05 / h, 2), 1e-9);
}

}  // namespace
}  // namespace weft::sim::remesh
