// End to end through the real `weft measure`: a small drape over a disc prints the table and
// writes measure.csv (DC = 1 for the flat sheet at t = 0, below 1 once it hangs) and
// outline.csv; a hang without a support measures only the settle time; --drape on a hang and a
// bad --frames are errors naming their cause, with nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "render/image.h"
#include "tests/app/cli_test_support.h"
#include "tests/support/test_files.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::test_files::read_csv;

class MeasureCli : public ::testing::Test {
 protected:
  void SetUp() override { m_dir = weft::app::test::fresh_test_directory("measure_cli"); }
  fs::path write_scene(const std::string& text) const {
    const fs::path path = m_dir / "scene.json";
    std::ofstream(path) << text;
    return path;
  }
  fs::path m_dir;
};

// A 30 cm sheet on 16×16 vertices dropped on a Ø12 cm disc (a cylinder 30 cm high) for `frames`
// frames at 24 fps; or, with `hang`, pinned at two corners with no obstacle.
std::string small_scene(bool hang) {
  const std::string obstacles = hang ? "" : R"(
  "obstacles": [{"cylinder": {"center": [0, 0, "15 cm"], "axis": [0, 0, 1], "radius": "6 cm", "height": "30 cm"}}],)";
  const std::string pins = hang ? R"(, "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}])" : "";
  return R"({
  "description": "weft measure test scene",
  "cloth": {"size": ["30 cm", "30 cm"], "resolution": [16, 16], "origin": ["-15 cm", "-15 cm", "30.5 cm"],
            "material": {"preset": "wool_kang_yu"})" + pins + R"(},)" + obstacles + R"(
  "simulation": {"air_damping": "5 1/s", "collision_friction": 0.5},
  "output": {"fps": 24, "frames": 12}
})";
}

TEST_F(MeasureCli, DrapeOverADiscWritesTheTableAndBothFiles) {
  const fs::path scene = write_scene(small_scene(false));
  const CommandResult r = run_weft("measure " + scene.string() + " --out " + m_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "drape over the cylinder obstacles[0]");
  EXPECT_CONTAINS(r.output, "settle time (max speed < 1 cm/s)");
  EXPECT_CONTAINS(r.output, "drape coefficient");
  EXPECT_CONTAINS(r.output, "folds");
  EXPECT_CONTAINS(r.output, "self-intersections at the end");

  const auto rows = read_csv(m_dir / "measure.csv");
  ASSERT_EQ(rows.size(), 14u);  // header + frames 0..12
  EXPECT_EQ(rows[0], (std::vector<std::string>{"frame", "time_s", "kinetic_energy_J", "max_speed_m_s",
                                                "drape_coefficient", "folds"}));
  // At t = 0 the sheet is flat: its shadow is the whole specimen, DC = 1 (to the raster's 1 %).
  EXPECT_NEAR(std::stod(rows[1][4]), 1.0, 0.01);
  EXPECT_EQ(std::stod(rows[1][3]), 0.0);  // at rest
  // After 0.5 s of falling the overhang hangs down: DC well below 1 and above 0.
  const double dc_end = std::stod(rows.back()[4]);
  EXPECT_LT(dc_end, 0.9);
  EXPECT_GT(dc_end, 0.0);
  EXPECT_NEAR(std::stod(rows.back()[1]), 0.5, 1e-9);

  const auto outline = read_csv(m_dir / "outline.csv");
  ASSERT_EQ(outline.size(), 361u);
  EXPECT_EQ(outline[0][0], "theta_deg");
  // No point of the outline lies inside the disc (the cloth covers it) or beyond the sheet's
  // half diagonal (it cannot stretch that far).
  for (std::size_t k = 1; k < outline.size(); ++k) {
    const double radius = std::stod(outline[k][1]);
    EXPECT_GT(radius, 0.06 - 0.002) << "bin " << k;
    EXPECT_LT(radius, 0.15 * std::sqrt(2.0) * 1.05) << "bin " << k;
  }
}

TEST_F(MeasureCli, AHangMeasuresOnlyTheSettleTime) {
  const fs::path scene = write_scene(small_scene(true));
  const CommandResult r = run_weft("measure " + scene.string() + " --frames 6 --out " + m_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "no support under the cloth");
  EXPECT_CONTAINS(r.output, "not settled by t = 0.25 s");  // still falling after 6 frames
  const auto rows = read_csv(m_dir / "measure.csv");
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows.back()[4], "");  // no DC
  EXPECT_GT(std::stod(rows.back()[3]), 0.1);
  EXPECT_FALSE(fs::exists(m_dir / "outline.csv"));
}

TEST_F(MeasureCli, DrapeWithoutSupportAndBadFramesAreErrors) {
  const fs::path scene = write_scene(small_scene(true));
  const fs::path out = m_dir / "out";
  CommandResult r = run_weft("measure " + scene.string() + " --drape --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, scene.string() + ": obstacles: --drape needs a support");
  r = run_weft("measure " + scene.string() + " --frames 0 --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "--frames 0: " + scene.string() +
                                ": output.frames: expected an integer in [1, 100000], got 0");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace

namespace {

// A top-view silhouette of a 6-node drape, r(θ) = 125 + 12 cos 6θ mm at 0.5 mm per pixel,
// white cloth on black, written as a PNG.
fs::path write_drape_silhouette(const fs::path& dir) {
  weft::render::Image image(600, 600);
  for (int y = 0; y < 600; ++y)
    for (int x = 0; x < 600; ++x) {
      const double dx = x - 300.0, dy = 300.0 - y;
      const double r_px = (125.0 + 12.0 * std::cos(6.0 * std::atan2(dy, dx))) / 0.5;
      if (std::hypot(dx, dy) < r_px) image.set(x, y, {255, 255, 255});
    }
  const fs::path path = dir / "drape.png";
  weft::render::write_png(image, path);
  return path;
}

}  // namespace

// weft measure --photo: the silhouette's DC (exact: (π(125² + 12²/2) − π90²)/(π150² − π90²)
// = 0.52757; the 0.5 mm pixels' error is about 1e-4) and its 6 nodes, the same table lines as a simulated drape, outline.csv and
// overlay.png.
TEST_F(MeasureCli, TopViewPhotoOfADrape) {
  const fs::path photo = write_drape_silhouette(m_dir);
  const fs::path out = m_dir / "photo_out";
  const CommandResult r = run_weft("measure --photo " + photo.string() +
                                   " --mm-per-px 0.5 --disc-mm 180 --specimen-mm 300 --out " +
                                   out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::size_t at = r.output.find("drape coefficient  ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NEAR(std::stod(r.output.substr(at + 19)), 0.52757, 0.002) << r.output;
  EXPECT_CONTAINS(r.output, "folds              6 at ");
  EXPECT_TRUE(fs::exists(out / "overlay.png"));
  EXPECT_EQ(read_csv(out / "outline.csv").size(), 361u);
}

TEST_F(MeasureCli, TopViewPhotoErrors) {
  const fs::path photo = write_drape_silhouette(m_dir);
  CommandResult r = run_weft("measure --photo " + photo.string() + " --mm-per-px 0.5 --disc-mm 180");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "--specimen-mm (the flat specimen's diameter, mm) must be a finite number > 0");
  r = run_weft("measure --photo " + photo.string() + " --disc-mm 180 --specimen-mm 300");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "exactly one of --mm-per-px and --disc-px");
  r = run_weft("measure --photo " + (m_dir / "nope.png").string() +
               " --mm-per-px 0.5 --disc-mm 180 --specimen-mm 300");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "nope.png: no such file");
  r = run_weft("measure scene.json --photo " + photo.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "excludes");
  r = run_weft("measure --photo " + photo.string() +
               " --mm-per-px 0.5 --disc-mm 180 --specimen-mm 300 --center-px 3,x");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "--center-px: expected X,Y");
}

// --until-settled simulates past output.frames until the max speed has stayed
// below 1 cm/s for 1 s, and stops there; a limit too short says "not settled".
TEST_F(MeasureCli, UntilSettledStopsOnceSettled) {
  const fs::path scene = write_scene(small_scene(true));  // damped hang, output.frames 12
  const CommandResult r =
      run_weft("measure " + scene.string() + " --until-settled '20 s' --out " + m_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("not settled"), std::string::npos) << r.output;
  const auto rows = read_csv(m_dir / "measure.csv");
  ASSERT_GT(rows.size(), 14u) << "ran past output.frames";
  const double end_s = std::stod(rows.back()[1]);
  EXPECT_LT(end_s, 20.0) << "stopped before the limit";
  // The last second is below 1 cm/s, and the frame before the settled second was not.
  std::size_t k = rows.size() - 1;
  for (; k > 1 && std::stod(rows[k][3]) < 0.01; --k) {
  }
  EXPECT_NEAR(end_s - std::stod(rows[k][1]), 1.0, 1.0 / 24 + 1e-9);

  const CommandResult short_limit =
      run_weft("measure " + scene.string() + " --until-settled 0.25 --out " + m_dir.string());
  ASSERT_EQ(short_limit.exit_code, 0) << short_limit.output;
  EXPECT_CONTAINS(short_limit.output, "not settled by t = 0.25 s");

  const CommandResult both = run_weft("measure " + scene.string() + " --until-settled --frames 3");
  EXPECT_EQ(both.exit_code, 1) << both.output;
  const CommandResult zero = run_weft("measure " + scene.string() + " --until-settled 0");
  EXPECT_EQ(zero.exit_code, 1) << zero.output;
  EXPECT_CONTAINS(zero.output, "--until-settled: expected a time in (0, 600] s");
}

namespace {

// weft measure --static over seeds and weft run --rest, through the command, on the bendstiff
// strip (a static solve of 0.01 s): one converged row per seed, the rest frame alone, and the
// options about time refused beside --rest.
TEST_F(MeasureCli, StaticSolvesOverSeedsAndTheRestFrame) {
  const std::string strip = std::string(WEFT_SOURCE_DIR) + "/assets/scenes/bendstiff_strip.json";
  const CommandResult m =
      run_weft("measure " + strip + " --static --seeds 2 --out " + (m_dir / "m").string());
  ASSERT_EQ(m.exit_code, 0) << m.output;
  EXPECT_NE(m.output.find("converged                    2 of 2"), std::string::npos) << m.output;
  const auto rows = read_csv(m_dir / "m" / "static.csv");
  ASSERT_EQ(rows.size(), 3u);  // the header and two seeds
  EXPECT_EQ(rows[1][0], "1");
  EXPECT_EQ(rows[2][0], "2");
  EXPECT_EQ(rows[1][1], "1");  // converged
  EXPECT_LE(std::stod(rows[1][4]), 1e-6);

  const CommandResult r =
      run_weft("run " + strip + " --rest --size 110x65 --out " + (m_dir / "r").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rest shape: static solve converged"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(m_dir / "r" / "frame_0001.png"));
  EXPECT_FALSE(fs::exists(m_dir / "r" / "frame_0002.png"));

  const CommandResult bad = run_weft("run " + strip + " --rest --frames 3 --out " + (m_dir / "b").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--rest"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(m_dir / "b"));
}

}  // namespace
