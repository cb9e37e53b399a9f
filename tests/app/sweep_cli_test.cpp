// End to end through the real `weft sweep`: a tiny sweep of the default scene writes a CSV with
// one row per combination and a plot, and bad --set input is reported before anything is run.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "render/image.h"
#include "tests/app/cli_test_support.h"
#include "tests/support/test_files.h"

namespace fs = std::filesystem;

namespace {

using SweepResult = weft::app::test::CommandResult;
using weft::test_files::read_csv;

SweepResult run_sweep_command(const std::string& args) {
  return weft::app::test::run_weft("sweep " + args);
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "sweep_cli" / name;
  fs::remove_all(dir);
  return dir;
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE((text).find(part), std::string::npos) << "missing: " << (part) << "\nin: " << (text)

// Two resolutions × two integrators of the default scene, 2 frames each.
TEST(SweepCli, GridOfTheDefaultSceneWritesCsvAndPlot) {
  const fs::path out = scratch("grid");
  const SweepResult r = run_sweep_command(
      "--set 'cloth.resolution=[8,8],[12,12]' --set simulation.integrator=symplectic_euler,"
      "velocity_verlet --frames 2 --out " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "run 4/4");
  EXPECT_CONTAINS(r.output, "Pareto-optimal settings");

  const auto rows = read_csv(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 5u);  // header + 2 × 2 runs
  const std::vector<std::string>& header = rows[0];
  EXPECT_EQ(header[1], "cloth.resolution");
  EXPECT_EQ(header[2], "simulation.integrator");
  const auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    ADD_FAILURE() << "no column " << name;
    return std::size_t{0};
  };
  int references = 0, pareto = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size()) << "row " << k;
    EXPECT_EQ(rows[k][column("diverged")], "0");
    EXPECT_GT(std::stol(rows[k][column("steps")]), 0);
    EXPECT_GT(std::stod(rows[k][column("wall_time_s")]), 0.0);
    const double rms = std::stod(rows[k][column("rms_error_m")]);
    if (rows[k][column("reference")] == "1") {
      ++references;
      EXPECT_EQ(rms, 0.0);  // the reference against itself
      EXPECT_EQ(std::stod(rows[k][column("silhouette_difference")]), 0.0);
      EXPECT_EQ(rows[k][column("pareto")], "1");  // nothing is closer to it than itself
    } else {
      // Different settings after 1/12 s of fall: apart, but by far less than the 1 m sheet.
      EXPECT_GT(rms, 0.0);
      EXPECT_LT(rms, 0.1);
    }
    pareto += rows[k][column("pareto")] == "1";
    const double silhouette = std::stod(rows[k][column("silhouette_difference")]);
    EXPECT_GE(silhouette, 0.0);
    EXPECT_LE(silhouette, 1.0);
  }
  EXPECT_EQ(references, 1);
  // The reference by the accuracy rule, never by time: the most vertices (12²), then the most
  // steps (both integrators take the same automatic step), then the first: run 3.
  EXPECT_EQ(rows[3][column("reference")], "1");
  EXPECT_CONTAINS(r.output, "errors against run 3 (resolution=[12,12] integrator=symplectic_euler), "
                            "the finest run that finished");
  EXPECT_GE(pareto, 1);
  EXPECT_EQ(rows[1][1], "[8,8]");  // last key varies fastest
  EXPECT_EQ(rows[2][1], "[8,8]");
  EXPECT_EQ(rows[2][2], "velocity_verlet");

  const weft::render::Image plot = weft::render::read_image(out / "sweep.png");
  EXPECT_GT(plot.width(), 0);
  EXPECT_TRUE(fs::exists(out / "scene.json"));
  EXPECT_TRUE(fs::exists(out / "run.txt"));
}

// Explicit Euler gains energy every step and blows up within 2 frames at 8×8 (51 steps): its
// row is marked diverged, without errors, and the sweep still succeeds against the other run.
TEST(SweepCli, DivergedRunIsARowNotAnError) {
  const fs::path out = scratch("diverged");
  const SweepResult r = run_sweep_command(
      "--set 'cloth.resolution=[8,8]' --set simulation.integrator=symplectic_euler,explicit_euler "
      "--frames 2 --out " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "diverged");
  const auto rows = read_csv(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 3u);
  const std::vector<std::string>& header = rows[0];
  ASSERT_EQ(header.size(), 13u);
  EXPECT_EQ(header[9], "diverged");
  EXPECT_EQ(header[12], "failed");
  EXPECT_EQ(rows[2][12], "0");  // diverged is a result, not a failure
  EXPECT_EQ(rows[1][9], "0");
  EXPECT_EQ(rows[1][11], "1");  // the reference: the only run that finished
  EXPECT_EQ(rows[2][9], "1");
  EXPECT_EQ(rows[2][6], "");    // rms_error_m: no last frame to compare
  EXPECT_EQ(rows[2][10], "0");  // never Pareto-optimal
  EXPECT_TRUE(fs::exists(out / "sweep.png"));
}

TEST(SweepCli, BadSetIsReportedBeforeAnythingRuns) {
  const fs::path out = scratch("bad");
  const SweepResult unknown =
      run_sweep_command("--set 'simulation.time_stp=1 ms,2 ms' --frames 1 --out " + out.string());
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_CONTAINS(unknown.output, "--set simulation.time_stp=1 ms");
  EXPECT_CONTAINS(unknown.output, "did you mean");
  EXPECT_EQ(unknown.output.find("run 1/"), std::string::npos) << unknown.output;
  EXPECT_FALSE(fs::exists(out));

  const SweepResult bad_value =
      run_sweep_command("--set 'cloth.resolution=[8,8],[0,8]' --frames 1 --out " + out.string());
  EXPECT_EQ(bad_value.exit_code, 1) << bad_value.output;
  EXPECT_CONTAINS(bad_value.output, "--set cloth.resolution=[0,8]");
  EXPECT_FALSE(fs::exists(out));

  const SweepResult reference = run_sweep_command(
      "--set 'cloth.resolution=[8,8]' --reference 2 --frames 1 --out " + out.string());
  EXPECT_EQ(reference.exit_code, 1) << reference.output;
  EXPECT_CONTAINS(reference.output, "--reference: expected a run number in 1..1, got 2");
  EXPECT_FALSE(fs::exists(out));

  const SweepResult missing = run_sweep_command("--frames 1 --out " + out.string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_CONTAINS(missing.output, "--set");
}

}  // namespace
