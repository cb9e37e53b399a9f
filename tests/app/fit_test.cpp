// weft fit: on targets made by weft itself with known parameters — measured
// cantilever numbers, a point cloud, a photo — the fit recovers the parameters (2 %, 5 %); and
// on the bendstiff photo it finds a bending rigidity that beats the authors' table's extremes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/fit/fit_optimizer.h"
#include "app/io/npy_file.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

const std::string kSource = WEFT_SOURCE_DIR;
const std::string kStrip = kSource + "/assets/scenes/bendstiff_strip.json";

fs::path test_dir(const std::string& name) {
  const fs::path dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "fit" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The bendstiff strip seen through a camera at 8× the photo's scale per pixel (274 × 161 px,
// 0.8808 mm/px), small enough for a fit test.
const std::string kSmallCamera = R"("render.size": [274, 161], "render.camera": {
    "intrinsics": {"fx": 56766.58, "fy": 56766.58, "cx": -0.5, "cy": 28.0, "size": [274, 161]},
    "position": [0, "-50 m", 0], "rotation": [[1, 0, 0], [0, 0, 1], [0, -1, 0]],
    "near": "49 m", "far": "51 m"})";

std::string fit_text(const std::string& set, const std::string& start, const std::string& target,
                     const std::string& extra = "") {
  return R"({"scene": ")" + kStrip + R"(", "set": {)" + set + R"(},
    "parameters": [{"name": "bend", "start": ")" + start + R"(", "min": "0.005 N*m", "max": "2 N*m"}],
    "target": )" + target + extra + R"(, "profile": {"points": 1, "span": 0.05}})";
}

// The settled strip at bending rigidity B, through a fit problem with any target.
Settled strip_at(double bend_Nm, const std::string& set = R"("render.msaa": 4)") {
  const FitSpec spec = parse_fit_spec(
      fit_text(set, "0.1 N*m", R"({"measured": {"drop": "1 cm"}})"), (test_dir("spec") / "f.json").string());
  FitProblem problem(spec);
  return settle_to_rest(problem.scene_at({bend_Nm}), spec.settle);
}

TEST(Fit, SensitivityBandIsWhereTheProfileCrossesTheLevel) {
  // f = (log10(v) − 0)², sampled at v = 10^-2 … 10^2: at band 1 the linear interpolation meets
  // the level exactly at v = 10^±1; at band 5 the right side never rises that far.
  const Profile p{{0.01, 0.1, 1.0, 10.0, 100.0}, {4.0, 1.0, 0.0, 1.0, 4.0}};
  const FittedParameter f = sensitivity_band(p, 2, 1.0);
  EXPECT_EQ(f.value, 1.0);
  EXPECT_NEAR(f.band_low, 0.1, 1e-12);
  EXPECT_NEAR(f.band_high, 10.0, 1e-12);
  EXPECT_FALSE(f.low_open || f.high_open);
  const FittedParameter wide = sensitivity_band(p, 2, 2.5);
  EXPECT_NEAR(std::log10(wide.band_low), -1.5, 1e-12);  // halfway from 1 to 4
  const FittedParameter open = sensitivity_band(p, 2, 5.0);
  EXPECT_TRUE(open.low_open && open.high_open);
  EXPECT_EQ(open.band_low, 0.01);
  EXPECT_EQ(open.band_high, 100.0);
}

TEST(Fit, ColumnMidlineDistanceOfTwoBands) {
  // Two horizontal bands, rows 10–12 and 14–18, over columns 5–29 and 0–19: their midlines
  // (rows 11 and 16) are 5 px apart in the 15 columns both cover.
  render::Mask a(40, 30), b(40, 30);
  for (int x = 5; x < 30; ++x)
    for (int y = 10; y <= 12; ++y) a.set(x, y, true);
  for (int x = 0; x < 20; ++x)
    for (int y = 14; y <= 18; ++y) b.set(x, y, true);
  EXPECT_DOUBLE_EQ(*column_midline_distance_px(a, b), 5.0);
  EXPECT_FALSE(column_midline_distance_px(a, render::Mask(40, 30)).has_value());
}

// Overhang and drop of the strip at B = 0.08 N·m, fitted from 0.03 N·m by `method`.
void expect_measured_recovery(const std::string& method) {
  const double truth = 0.08;
  const Settled s = strip_at(truth);
  ASSERT_TRUE(s.converged);
  const CantileverShape c = measure_cantilever(*s.simulator);
  // A cantilever of 250 mm: the tip below the clamp and short of the full length.
  EXPECT_GT(c.drop_m, 0.02);
  EXPECT_LT(c.overhang_m, 0.25);
  char target[200];
  std::snprintf(target, sizeof target,
                R"({"measured": {"overhang": "%.9g m", "drop": "%.9g m"}}, "optimizer": {"method": "%s"})",
                c.overhang_m, c.drop_m, method.c_str());
  const FitSpec spec = parse_fit_spec(fit_text(R"("render.msaa": 4)", "0.03 N*m", target),
                                      (test_dir("measured_" + method) / "f.json").string());
  FitProblem problem(spec);
  const FitResult r = run_fit(problem);
  std::printf("%s: fitted B %.6g N·m, truth %.6g N·m (%+.3f %%), objective %.4g, %zu evaluations\n",
              method.c_str(), r.best.values[0], truth, 100.0 * (r.best.values[0] / truth - 1.0),
              r.best.objective, r.evaluations.size());
  EXPECT_NEAR(r.best.values[0] / truth, 1.0, 0.02) << r.stop_reason;
  EXPECT_LT(r.fitted[0].band_low, r.best.values[0]);
  EXPECT_GT(r.fitted[0].band_high, r.best.values[0]);
}

TEST(Fit, MeasuredOverhangAndDropRecoverBendingWithin2Percent) { expect_measured_recovery("bobyqa"); }

TEST(Fit, NelderMeadRecoversTheSameWithin2Percent) { expect_measured_recovery("nelder_mead"); }

// A one-parameter fit's B within `relative` of `truth`, its objective below `objective_below`.
void expect_recovered(const FitResult& r, double truth, double relative, double objective_below) {
  std::printf("fitted B %.6g N·m, truth %.6g N·m (%+.3f %%), objective %.4g, %zu evaluations\n",
              r.best.values[0], truth, 100.0 * (r.best.values[0] / truth - 1.0), r.best.objective,
              r.evaluations.size());
  EXPECT_NEAR(r.best.values[0] / truth, 1.0, relative) << r.stop_reason;
  EXPECT_LT(r.best.objective, objective_below);
}

TEST(Fit, PointCloudRecoversBendingWithin2Percent) {
  const double truth = 0.03;
  const Settled s = strip_at(truth);
  const fs::path dir = test_dir("point_cloud");
  write_npy_points(dir / "cloud.npy", s.simulator->state().x);
  const FitSpec spec = parse_fit_spec(
      fit_text(R"("render.msaa": 4)", "0.1 N*m", R"({"point_cloud": {"file": "cloud.npy"}})"),
      (dir / "f.json").string());
  FitProblem problem(spec);
  const FitResult r = run_fit(problem);
  expect_recovered(r, truth, 0.02, 0.5);  // objective in mm
}

TEST(Fit, SilhouetteRecoversBendingWithin5Percent) {
  const double truth = 0.04;
  const fs::path dir = test_dir("silhouette");
  {
    const FitSpec spec = parse_fit_spec(
        fit_text(kSmallCamera, "0.1 N*m", R"({"measured": {"drop": "1 cm"}})"), (dir / "f.json").string());
    FitProblem problem(spec);
    const Scene scene = problem.scene_at({truth});
    const Settled s = settle_to_rest(scene, spec.settle);
    render::write_png(problem.render_look(scene, *s.simulator), dir / "photo.png");
  }
  const FitSpec spec = parse_fit_spec(
      fit_text(kSmallCamera, "0.1 N*m", R"({"photo": {"image": "photo.png", "mm_per_px": 0.8808}})"),
      (dir / "f.json").string());
  FitProblem problem(spec);
  const FitResult r = run_fit(problem);
  expect_recovered(r, truth, 0.05, 1.0);  // objective in px
}

// A 20 cm square plate clamped at one corner (bend_warp 2e-3, bend_weft 5e-3 N·m, 200 g/m²)
// bends along both the warp and the weft, written to dir/plate.json, and its point cloud at rest
// to dir/cloud.npy.
void write_corner_clamped_plate(const fs::path& dir) {
  std::ofstream(dir / "plate.json") << R"({"description": "corner-clamped plate",
    "cloth": {"size": ["20 cm", "20 cm"], "resolution": [11, 11], "origin": [0, 0, 0],
      "warp_axis": [1, 0, 0], "weft_axis": [0, 1, 0],
      "material": {"density": "200 g/m^2", "bend_warp": "2e-3 N*m", "bend_weft": "5e-3 N*m"},
      "pins": [{"region": {"u": [0, 0.1], "v": [0, 0.1]}}]},
    "simulation": {"integrator": "dynamic_relaxation"}, "output": {"frames": 1},
    "render": {"ground": {"collider": false}}})";  // the plate starts at z = 0 and sags below it
  const Scene scene = load_scene(dir / "plate.json");
  const Settled s = settle_to_rest(scene, SettleSettings{});
  write_npy_points(dir / "cloud.npy", cloth_points(s.simulator->mesh(), s.simulator->state().x));
}

// The fit of `parameters` (a JSON array) to the plate's own point cloud.
FitResult fit_plate(const fs::path& dir, const std::string& parameters) {
  const FitSpec spec = parse_fit_spec(
      R"({"scene": "plate.json", "parameters": )" + parameters +
          R"(, "target": {"point_cloud": {"file": "cloud.npy"}}, "profile": {"points": 1, "span": 0.05}})",
      (dir / "f.json").string());
  FitProblem problem(spec);
  return run_fit(problem);
}

// The plate's shape fixes both rigidities, and two parameters take the BOBYQA path.
TEST(Fit, TwoRigiditiesOfACornerClampedPlateFromItsPointCloud) {
  const fs::path dir = test_dir("plate");
  write_corner_clamped_plate(dir);
  const FitResult r = fit_plate(dir, R"([{"name": "bend_warp", "start": "1e-3 N*m"},
                                         {"name": "bend_weft", "start": "1e-2 N*m"}])");
  std::printf("fitted bend_warp %.5g, bend_weft %.5g N·m (truth 2e-3, 5e-3), objective %.3g mm, "
              "%zu evaluations (%s)\n", r.best.values[0], r.best.values[1], r.best.objective,
              r.evaluations.size(), r.stop_reason.c_str());
  EXPECT_NEAR(r.best.values[0] / 2e-3, 1.0, 0.02);
  EXPECT_NEAR(r.best.values[1] / 5e-3, 1.0, 0.02);
}

// With the rigidities known, the plate's droop fixes its weight: the density parameter (fitted
// for the φ-SfT scarf) recovers 200 g/m² from a start half as heavy.
TEST(Fit, DensityOfACornerClampedPlateFromItsPointCloud) {
  const fs::path dir = test_dir("plate_density");
  write_corner_clamped_plate(dir);
  const FitResult r = fit_plate(dir, R"([{"name": "density", "start": "100 g/m^2"}])");
  std::printf("fitted density %.5g kg/m² (truth 0.2), objective %.3g mm, %zu evaluations (%s)\n",
              r.best.values[0], r.best.objective, r.evaluations.size(), r.stop_reason.c_str());
  EXPECT_NEAR(r.best.values[0] / 0.2, 1.0, 0.02);
}

}  // namespace
}  // namespace weft::app
