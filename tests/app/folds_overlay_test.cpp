// weft folds' pieces in app/: the photo overlay (lines land on the predicted wrinkle curves,
// positive solid black, negative dashed white; the supports and --bottom place them), the
// parsing and placement errors, and the JSON fields.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/cli/folds_command.h"
#include "app/report/folds_overlay.h"
#include "app/scene/scene.h"

namespace weft::app {
namespace {

const render::Rgb8 kGrey{128, 128, 128};

sim::TensionFieldInputs table1_row2() {
  sim::TensionFieldInputs in;
  in.height_m = 1.40;
  in.width_m = 1.40;
  in.support_shift_m = 0.10;
  in.thickness_m = 0.25e-3;
  in.youngs_modulus_Pa = 165e6;
  in.weight_N_m2 = 1.5;
  in.ratio = 1.29;
  return in;
}

sim::FoldPattern row2_pattern() {
  const sim::TensionFieldInputs in = table1_row2();
  return sim::make_fold_pattern(in, sim::solve_tension_field(in));
}

OverlayPlacement supports(double x1, double y1, double x2, double y2) {
  OverlayPlacement p;
  p.left_support_px = {x1, y1};
  p.right_support_px = {x2, y2};
  return p;
}

TEST(FoldsOverlay, MappingPutsTheSupportsAndTheBottomWhereGiven) {
  const sim::FoldPattern p = row2_pattern();
  OverlayPlacement placement = supports(40, 30, 360, 30);
  const OverlayMapping m = overlay_mapping(p, placement, 400, 500);
  EXPECT_NEAR((m.to_pixel(-0.5 * p.span_m, 0.0) - Eigen::Vector2d(40, 30)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((m.to_pixel(0.5 * p.span_m, 0.0) - Eigen::Vector2d(360, 30)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(m.down_px_per_m.y(), 320 / p.span_m, 1e-9);  // same scale as across
  placement.bottom_px = 450;
  const OverlayMapping b = overlay_mapping(p, placement, 400, 500);
  EXPECT_NEAR(b.to_pixel(0.0, sim::fibre_point(p, 0.0, p.height_m).depth_m).y(), 450.0, 1e-9);
}

// Every sample of a positive line is black; a negative line is white on part of its length
// only (dashed); far from the lines the photo is untouched. Samples within 0.3 l of the
// supports are left out: there all lines converge and later ones draw over earlier ones.
TEST(FoldsOverlay, LinesLandOnThePredictedCurves) {
  const sim::FoldPattern p = row2_pattern();
  const render::Image photo(400, 500, kGrey);
  const OverlayMapping m = overlay_mapping(p, supports(40, 30, 360, 30), 400, 500);
  const render::Image out = draw_fold_overlay(photo, p, m);
  const int samples = 400;
  for (int i = 0; i <= p.top_line(); ++i) {
    int black = 0, white = 0, inside = 0;
    for (int k = 0; k <= samples; ++k) {
      const double x = 0.4 * p.span_m * (2.0 * k / samples - 1.0);  // |x| ≤ 0.4 l
      const Eigen::Vector2d px = m.to_pixel(x, sim::wrinkle_depth_m(p, i, x));
      const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
      if (u < 0 || v < 0 || u >= out.width() || v >= out.height()) continue;
      ++inside;
      // Within a pixel of the curve: the lines are chords of it, 2 pixels wide.
      bool has_black = false, has_white = false;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) {
          has_black |= out.at(u + du, v + dv) == render::Rgb8{0, 0, 0};
          has_white |= out.at(u + du, v + dv) == render::Rgb8{255, 255, 255};
        }
      black += has_black;
      white += has_white;
    }
    ASSERT_EQ(inside, samples + 1) << "line " << i;
    if (sim::wrinkle_sign(i) > 0) {
      EXPECT_EQ(black, inside) << "positive line " << i;
    } else {
      EXPECT_GT(white, inside / 3) << "negative line " << i;
      EXPECT_LT(white, inside * 9 / 10) << "negative line " << i << " is not dashed";
    }
  }
  EXPECT_EQ(out.at(5, 495), kGrey);
  EXPECT_EQ(out.at(395, 5), kGrey);
}

TEST(FoldsOverlay, BadPlacementIsAnErrorNamingTheFlag) {
  const sim::FoldPattern p = row2_pattern();
  const auto message = [&](const OverlayPlacement& placement) -> std::string {
    try {
      (void)overlay_mapping(p, placement, 400, 300);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message(supports(40, 30, 420, 30)).find("--supports"), std::string::npos);
  EXPECT_NE(message(supports(40, 30, 420, 30)).find("400x300"), std::string::npos);
  EXPECT_NE(message(supports(-1, 30, 200, 30)).find("outside"), std::string::npos);
  EXPECT_NE(message(supports(40, 30, 40, 30)).find("apart"), std::string::npos);
  OverlayPlacement above = supports(40, 100, 360, 100);
  above.bottom_px = 50;  // above the supports
  EXPECT_NE(message(above).find("--bottom"), std::string::npos);
  EXPECT_THROW(parse_supports("1,2,3"), InputError);
  EXPECT_THROW(parse_supports("1,2,3,x"), InputError);
  EXPECT_THROW(parse_supports("1,2,3,4,5"), InputError);
  EXPECT_THROW(parse_supports("1,2,3,nan"), InputError);
  const OverlayPlacement ok = parse_supports("10,20.5,30,40");
  EXPECT_EQ(ok.right_support_px, Eigen::Vector2d(30, 40));
}

TEST(FoldsJson, HoldsTheResultFields) {
  const sim::TensionFieldInputs in = table1_row2();
  const sim::TensionFieldResult r = sim::solve_tension_field(in);
  const nlohmann::json j = folds_json(in, r);
  for (const char* key : {"inputs", "span_m", "critical_stress_Pa", "Q", "Q_given", "n", "z_max_m",
                          "amplitudes_m", "boundary_length_m", "relative_error", "status",
                          "converged", "message"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["n"].get<int>(), r.wrinkles);
  EXPECT_EQ(j["amplitudes_m"].size(), static_cast<std::size_t>(r.wrinkles) + 1);
  EXPECT_EQ(j["status"], "converged");
  EXPECT_EQ(folds_flag("t"), "--t/--t-mm");
  EXPECT_EQ(folds_flag("w"), "--w/--w-N-mm2");
}

}  // namespace
}  // namespace weft::app
