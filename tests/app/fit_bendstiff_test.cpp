// The bendstiff evidence: the cantilevered strip of Broberg et al.'s photo
// (tests/data/photos/bendstiff/, 4× downscaled: 548 × 323 px, 0.4404 mm/px), its bending
// rigidity fitted by weft fit from the photo alone, against the authors' own table of midline,
// curvature and moment (simulator_results.csv, converted from their xlsx by
// scripts/xlsx_to_csv.py), which gives B = moment / curvature along the strip.
#include <gtest/gtest.h>

#include "sim/material/bending_law.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/fit/fit_optimizer.h"

namespace weft::app {
namespace {

const std::string kData = std::string(WEFT_SOURCE_DIR) + "/tests/data/photos/bendstiff/";

struct TableRow {
  double x_m, y_m, curvature_1_m, moment_N;  // moment per width: N·m/m
};

std::vector<TableRow> read_table() {
  std::ifstream in(kData + "simulator_results.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,curvature,moment");
  std::vector<TableRow> rows;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    TableRow r{};
    fields >> r.x_m >> r.y_m >> r.curvature_1_m >> r.moment_N;
    rows.push_back(r);
  }
  return rows;
}

// The bendstiff fit (assets/fits/bendstiff.json) on the 4× copy of the photo.
std::string fit_text() {
  return R"({"scene": ")" + std::string(WEFT_SOURCE_DIR) + R"(/assets/scenes/bendstiff_strip.json",
    "set": {"render.size": [548, 323], "render.camera": {
      "intrinsics": {"fx": 113533.15, "fy": 113533.15, "cx": -0.5, "cy": 56.5, "size": [548, 323]},
      "position": [0, "-50 m", 0], "rotation": [[1, 0, 0], [0, 0, 1], [0, -1, 0]],
      "near": "49 m", "far": "51 m"}},
    "parameters": [{"name": "bend", "start": "0.1 N*m", "min": "0.005 N*m", "max": "2 N*m"}],
    "target": {"photo": {"image": ")" + kData + R"(example_image_x4.png", "mm_per_px": 0.4404}},
    "profile": {"points": 2, "span": 0.1}})";
}

double measure(const Evaluation& e, const std::string& name) {
  for (const auto& [n, v] : e.measures)
    if (n == name) return v;
  ADD_FAILURE() << "no measure " << name;
  return NAN;
}

TEST(Bendstiff, TableMomentIsTheWeightOfTheStripBeyond) {
  // The table's moment at the clamp is the moment of the strip's own weight (13.6 N/m² times
  // the lever arm, summed along its own midline): that fixes its unit as N·m per metre width.
  const std::vector<TableRow> t = read_table();
  ASSERT_EQ(t.size(), 51u);
  double arc_m = 0.0, moment = 0.0;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double ds = std::hypot(t[i + 1].x_m - t[i].x_m, t[i + 1].y_m - t[i].y_m);
    arc_m += ds;
    moment += 13.6 * ds * 0.5 * (t[i].x_m + t[i + 1].x_m);
  }
  std::printf("table: arc length %.4f m, weight moment at the clamp %.4f N, table %.4f N\n", arc_m,
              moment, t[0].moment_N);
  EXPECT_NEAR(arc_m, 0.250, 0.001);  // the scene's strip length
  EXPECT_NEAR(moment / t[0].moment_N, 1.0, 0.03);
}

TEST(Bendstiff, FitFromThePhotoLiesBetweenTheTablesStiffnesses) {
  // B = M/κ along the strip: about 0.02 N·m at the clamp (κ ≈ 20 /m) and 0.48 N·m where it is
  // nearly straight (κ < 1 /m) — a moment–curvature relation far from linear.
  double b_min = INFINITY, b_max = 0.0;
  for (const TableRow& r : read_table()) {
    if (!(r.curvature_1_m > 0.0)) continue;
    const double b = r.moment_N / r.curvature_1_m;
    std::printf("table: x %.4f m  curvature %8.4f /m  moment %.5f N  B = M/κ %.4f N·m\n", r.x_m,
                r.curvature_1_m, r.moment_N, b);
    b_min = std::min(b_min, b);
    b_max = std::max(b_max, b);
  }
  const FitSpec spec = parse_fit_spec(fit_text(), kData + "bendstiff_test_fit.json");
  FitProblem problem(spec);
  const FitResult r = run_fit(problem);
  const double b = r.best.values[0];
  const Evaluation soft = problem.evaluate({b_min}), stiff = problem.evaluate({b_max});
  std::printf("fitted B %.4g N·m (band %.4g … %.4g) after %zu evaluations: IoU %.3f, outline "
              "Chamfer %.2f px = %.2f mm, midline distance %.2f mm; table B %.4g … %.4g N·m give "
              "midline distances %.2f, %.2f mm\n",
              b, r.fitted[0].band_low, r.fitted[0].band_high, r.evaluations.size(),
              measure(r.best, "iou"), measure(r.best, "chamfer_px"), measure(r.best, "chamfer_mm"),
              measure(r.best, "midline_mm"), b_min, b_max, measure(soft, "midline_mm"),
              measure(stiff, "midline_mm"));
  EXPECT_GT(b, b_min);
  EXPECT_LT(b, b_max);
  EXPECT_TRUE(r.best.settled);
  // The fitted strip follows the photo better than either constant stiffness of the table.
  EXPECT_LT(measure(r.best, "midline_mm"), 0.5 * measure(soft, "midline_mm"));
  EXPECT_LT(measure(r.best, "midline_mm"), 0.5 * measure(stiff, "midline_mm"));
  // A linear-elastic strip cannot bend as sharply at the clamp as the fabric does; what is
  // left is a few millimetres along a 250 mm strip.
  EXPECT_LT(measure(r.best, "midline_mm"), 8.0);
}

// The same photo with Grosberg's frictional law (assets/fits/bendstiff_nonlinear.json, on the
// 2× copy, each evaluation a static solve): the midline within a millimetre, and the fitted
// curve M(κ) beside the authors' table, which it was never shown.
TEST(Bendstiff, FrictionalBendingLawFollowsThePhotoWithinAMillimetreAndTheTable) {
  const FitSpec spec = load_fit_spec(std::string(WEFT_SOURCE_DIR) + "/assets/fits/bendstiff_nonlinear.json");
  FitProblem problem(spec);
  const FitResult r = run_fit(problem);
  const sim::BendingLaw law =
      sim::BendingLaw::frictional(r.best.values[0], r.best.values[1], r.best.values[2]);
  std::printf("fitted %s after %zu evaluations: outline Chamfer %.2f mm, midline distance %.2f mm\n",
              law.describe().c_str(), r.evaluations.size(), measure(r.best, "chamfer_mm"),
              measure(r.best, "midline_mm"));
  EXPECT_TRUE(r.best.settled);
  EXPECT_LE(measure(r.best, "midline_mm"), 1.0);
  double worst_high = 0.0;  // where the strip is bent (κ ≥ 1 /m)
  for (const TableRow& row : read_table()) {
    if (!(row.curvature_1_m > 0.0)) continue;
    const double m = law.moment(row.curvature_1_m);
    std::printf("table: curvature %8.4f /m  moment %.4f N  fitted law %.4f N\n", row.curvature_1_m,
                row.moment_N, m);
    if (row.curvature_1_m >= 1.0) worst_high = std::max(worst_high, std::abs(m / row.moment_N - 1.0));
  }
  EXPECT_LT(worst_high, 0.05);
}

}  // namespace
}  // namespace weft::app
