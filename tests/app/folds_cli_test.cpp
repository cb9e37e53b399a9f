// End to end through the real `weft folds`: Table 1 and the §6 example of seed 001 from the
// command line (text and --json), an overlay PNG written, and bad input — t <= 0, d >= L, a
// missing photo, supports outside it — rejected with exit code 1 naming the flag.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;

::testing::AssertionResult has_text(const std::string& output, const std::string& part) {
  if (output.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "missing: " << part << "\nin: " << output;
}

const std::string kTable1 = " --L-cm 140 --d-cm 10 --t-mm 0.25 --E-MPa 165 --w-N-mm2 15e-7";

fs::path test_dir(const char* name) {
  const fs::path dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "folds_cli" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(FoldsCli, Table1FromTheCommandLine) {
  struct Row {
    const char* h;
    const char* q;
    int n;
    double z_max_cm;
  };
  for (const Row& row : {Row{"90", "1.31", 5, 5.4}, Row{"140", "1.29", 7, 4.8}, Row{"235", "1.34", 8, 6.0}}) {
    const CommandResult r =
        run_weft(std::string("folds --h-cm ") + row.h + kTable1 + " --Q " + row.q + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(r.output);
    EXPECT_EQ(j["n"].get<int>(), row.n) << "h = " << row.h;
    EXPECT_NEAR(100.0 * j["z_max_m"].get<double>(), row.z_max_cm, 0.2 * row.z_max_cm);
    EXPECT_TRUE(j["converged"].get<bool>());
  }
  const CommandResult text = run_weft(
      "folds --h-cm 140 --L-cm 140 --d-cm 10 --t-mm 0.4 --E-MPa 140 --w-N-mm2 17.7e-7 --Q 1.29");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_TRUE(has_text(text.output, "n         7\n"));
  EXPECT_TRUE(has_text(text.output, "converged"));
}

TEST(FoldsCli, OverlayWritesAPng) {
  const fs::path dir = test_dir("overlay");
  weft::render::write_png(weft::render::Image(300, 300, {90, 100, 110}), dir / "photo.png");
  const CommandResult r = run_weft("folds --h-cm 140" + kTable1 + " --Q 1.29 --overlay " +
                                   (dir / "photo.png").string() + " --supports 20,20,280,20 --out " +
                                   (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const weft::render::Image out = weft::render::read_image(dir / "out" / "folds_overlay.png");
  EXPECT_EQ(out.width(), 300);
  EXPECT_EQ(out.height(), 300);
}

TEST(FoldsCli, BadInputNamesTheFlag) {
  const fs::path dir = test_dir("bad");
  CommandResult r = run_weft("folds --h-cm 140 --L-cm 140 --d-cm 10 --t-mm 0 --E-MPa 165 --w-N-mm2 15e-7");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has_text(r.output, "--t-mm"));
  r = run_weft("folds --h-cm 140 --L-cm 140 --d-cm 150 --t-mm 0.25 --E-MPa 165 --w-N-mm2 15e-7");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has_text(r.output, "--d-cm"));
  r = run_weft("folds --h-cm nan" + kTable1);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has_text(r.output, "--h-cm"));
  r = run_weft("folds --h-cm 140" + kTable1 + " --overlay " + (dir / "none.png").string() +
               " --supports 1,1,5,1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has_text(r.output, "no such file"));
  weft::render::write_png(weft::render::Image(100, 80, {}), dir / "photo.png");
  r = run_weft("folds --h-cm 140" + kTable1 + " --overlay " + (dir / "photo.png").string() +
               " --supports 10,10,150,10 --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has_text(r.output, "--supports"));
  EXPECT_FALSE(fs::exists(dir / "out"));  // nothing written
}

// The inputs take unit strings like a scene file's values (--t "0.25 mm",
// any length or stress unit); the result is the paper-unit flags' to the last digit. Both forms
// of one input, a missing input, a missing unit and a unit of the wrong kind are errors naming
// the flag.
TEST(FoldsCli, InputsTakeUnitStringsLikeSceneFiles) {
  const CommandResult paper = run_weft("folds --h-cm 140" + kTable1 + " --json");
  ASSERT_EQ(paper.exit_code, 0) << paper.output;
  const CommandResult units = run_weft(
      "folds --h '1.4 m' --L '140 cm' --d '100 mm' --t '0.25 mm' --E '0.165 GPa' "
      "--w '1.5 Pa' --json");
  ASSERT_EQ(units.exit_code, 0) << units.output;
  const nlohmann::json a = nlohmann::json::parse(paper.output);
  const nlohmann::json b = nlohmann::json::parse(units.output);
  for (const char* key : {"height_m", "width_m", "support_shift_m", "thickness_m",
                          "youngs_modulus_Pa", "weight_N_m2"})
    EXPECT_NEAR(b["inputs"][key].get<double>(), a["inputs"][key].get<double>(),
                1e-12 * std::abs(a["inputs"][key].get<double>())) << key;
  EXPECT_EQ(b["n"], a["n"]);
  EXPECT_NEAR(b["z_max_m"].get<double>(), a["z_max_m"].get<double>(), 1e-9);
  // The two forms mix: one flag each.
  const CommandResult mixed = run_weft("folds --h '140 cm'" + kTable1 + " --json");
  ASSERT_EQ(mixed.exit_code, 0) << mixed.output;
  EXPECT_EQ(nlohmann::json::parse(mixed.output)["n"], a["n"]);

  const std::string rest = " --L-cm 140 --d-cm 10 --E-MPa 165 --w-N-mm2 15e-7";
  struct Bad {
    const char* t;                        // the thickness flags given
    std::vector<const char*> messages;  // each in the output
  };
  for (const Bad& bad : {Bad{" --t '0.25 mm' --t-mm 0.25", {"--t", "excludes"}},
                         Bad{"", {"--t (or --t-mm) is required"}},
                         Bad{" --t 0.25", {"--t: expected a length", "the unit is missing"}},
                         Bad{" --t '0.25 MPa'", {"--t: expected a length"}},
                         Bad{" --t '2 m'", {"--t: expected a value in (0, 0.1] m, got '2 m'"}}}) {
    const CommandResult r = run_weft(std::string("folds --h-cm 140") + bad.t + rest);
    EXPECT_EQ(r.exit_code, 1) << bad.t << "\n" << r.output;
    for (const char* message : bad.messages) EXPECT_TRUE(has_text(r.output, message)) << bad.t;
  }
}

}  // namespace
