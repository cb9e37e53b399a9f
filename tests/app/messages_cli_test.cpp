// Messages of the real `weft`: a mistyped command is named with a suggestion,
// errors point at the command's own --help, `weft` alone prints usage with the program name,
// the run summary goes to stderr with "frame" in the singular for one, and a time step above the
// explicit integrator's critical step is warned of up front, and so is a ray-tracer option given
// to the rasterizer. An explicit integrator with fast projection at a tolerance that lets the
// cloth jitter is warned of, and the warning is right: that cloth does not settle. A fixed step
// whose projections miss their tolerance is told of the adaptive step, and the advice is right:
// the adaptive step misses far fewer.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <string>

#include "tests/app/cli_test_support.h"
#include "tests/support/test_files.h"

namespace {

namespace fs = std::filesystem;

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class MessagesCli : public CliDirectoryTest {
 protected:
  MessagesCli() : CliDirectoryTest("messages_cli") {}
};

TEST_F(MessagesCli, ATypoNamesTheCommandAndSuggestsOne) {
  const auto typo = run_weft("rnu scene.json");
  EXPECT_EQ(typo.exit_code, 1) << typo.output;
  EXPECT_CONTAINS(typo.output, "unknown command 'rnu' (did you mean 'run'?)");
  const auto far = run_weft("xyzzy");
  EXPECT_EQ(far.exit_code, 1) << far.output;
  EXPECT_CONTAINS(far.output, "unknown command 'xyzzy'; see weft --help");
  const auto option = run_weft("run --no-such-option");
  EXPECT_EQ(option.exit_code, 1) << option.output;
  EXPECT_CONTAINS(option.output, "(see weft run --help)");
  const auto alone = run_weft("");
  EXPECT_EQ(alone.exit_code, 1) << alone.output;
  EXPECT_CONTAINS(alone.output, "Usage: weft ");
}

TEST_F(MessagesCli, TheRunSummaryGoesToStderrInTheRightNumber) {
  const std::string scene = write_scene("tiny.json", tiny_scene()).string();
  const std::string out = (m_dir / "out").string();
  const auto both = run_weft("run " + scene + " --frames 1 --out " + out);
  EXPECT_EQ(both.exit_code, 0) << both.output;
  EXPECT_CONTAINS(both.output, "wrote 1 frame to ");
  EXPECT_CONTAINS(both.output, " — 1 frame at 24 fps");
  const auto stdout_only = run_weft("run " + scene + " --frames 1 --out " + out + " 2>/dev/null | cat");
  EXPECT_EQ(stdout_only.output.find("wrote"), std::string::npos) << stdout_only.output;
}

TEST_F(MessagesCli, ATimeStepAboveTheCriticalOneIsWarnedOfUpFront) {
  const std::string scene = write_scene("tiny.json", tiny_scene()).string();
  const auto r = run_weft("run " + scene + " --frames 1 --set simulation.time_step=5ms --out " +
                          (m_dir / "out").string());
  EXPECT_CONTAINS(r.output, "exceeds the predicted critical step");
  // The warning comes before the first frame's progress line.
  EXPECT_LT(r.output.find("exceeds the predicted critical step"), r.output.find("frame 1/1"))
      << r.output;
  const auto fine = run_weft("run " + scene + " --frames 1 --out " + (m_dir / "out2").string());
  EXPECT_EQ(fine.output.find("exceeds"), std::string::npos) << fine.output;
}

// The default hang on 21² vertices with symplectic Euler (h = 1.93 ms, |g| h² / edge = 7.3e-4)
// and fast projection: at tolerance 3e-3 the projection acts only every few steps and its
// corrections keep the sheet moving after 3 s of damping at 5/s; at 1e-4 it acts every step and
// the sheet comes to rest.
TEST_F(MessagesCli, AnExplicitStepWithAProjectionThatWouldJitterIsWarnedOf) {
  const auto kinetic_energy_at_the_end = [&](const std::string& tolerance, std::string& output) {
    const std::filesystem::path out = m_dir / ("hang_" + tolerance);
    const auto r = run_weft("run --set cloth.resolution=[21,21] --set "
                            "'simulation.constraints={\"method\":\"fast_projection\",\"tolerance\":" +
                            tolerance + "}' --last --size 64x48 --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    output = r.output;
    return weft::test_files::csv_column(weft::test_files::read_csv(out / "stats.csv"),
                                        "kinetic_energy_J")
        .back();
  };
  std::string loose_output, tight_output;
  const double loose = kinetic_energy_at_the_end("3e-3", loose_output);
  const double tight = kinetic_energy_at_the_end("1e-4", tight_output);
  EXPECT_CONTAINS(loose_output, "warning: simulation.constraints.tolerance 0.003 is more than twice");
  EXPECT_EQ(tight_output.find("warning"), std::string::npos) << tight_output;
  // The sheet (0.19 kg) still moves at centimetres per second, against micrometres at rest.
  EXPECT_GT(loose, 1e-3);
  EXPECT_LT(tight, 1e-5);
}

// Explicit bending past its limit crumples the free hem (sim's InextensibleCloth tests): the
// inextensible hang on 96² vertices at 1/120 s is past it (the 1 m wool's limit there is about
// 5 ms), so forcing "explicit" is warned of up front, and "auto", which then takes the bending
// into the matrix, is not.
TEST_F(MessagesCli, ExplicitBendingPastItsStableStepIsWarnedOf) {
  const auto run = [&](const std::string& bending) {
    return run_weft("run " + std::string(WEFT_SOURCE_DIR) + "/assets/scenes/hang_inextensible.json" +
                    " --set cloth.resolution=[96,96] --set simulation.bending_in_step=" + bending +
                    " --frames 1 --size 64x48 --out " + (m_dir / bending).string());
  };
  const auto forced = run("explicit");
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
  const std::string warning = "warning: the bending is explicit (simulation.bending_in_step \"explicit\") at steps of 8.33 ms, past its stable ";
  const std::size_t at = forced.output.find(warning);
  ASSERT_NE(at, std::string::npos) << forced.output;
  const double stable_ms = std::stod(forced.output.substr(at + warning.size()));
  EXPECT_GT(stable_ms, 3.0);
  EXPECT_LT(stable_ms, 8.33);
  EXPECT_LT(at, forced.output.find("frame 1/1")) << "warned before the first frame";
  const auto automatic = run("auto");
  EXPECT_EQ(automatic.exit_code, 0) << automatic.output;
  EXPECT_EQ(automatic.output.find("bending is explicit"), std::string::npos) << automatic.output;
}

// The inextensible hang on 41² vertices with one 1/24 s step per frame and at most 2 projection
// iterations per step: the predictions lie far from the constraints and nearly every step
// misses; the adaptive step shortens the steps until 2 iterations do.
TEST_F(MessagesCli, MissedProjectionsOfAFixedStepAreToldOfTheAdaptiveStep) {
  // The fraction of the steps that missed; `output` gets weft's messages.
  const auto missed = [&](const std::string& name, const std::string& step, std::string& output) {
    const std::filesystem::path out = m_dir / name;
    const auto r = run_weft("run " + std::string(WEFT_SOURCE_DIR) + "/assets/scenes/hang_inextensible.json" +
                            " --set cloth.resolution=[41,41] --set 'simulation.time_step=" + step +
                            "' --set simulation.constraints.max_iterations=2 --frames 24 --last "
                            "--size 64x48 --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    output = r.output;
    const auto rows = weft::test_files::read_csv(out / "stats.csv");
    const std::vector<double> unconverged = weft::test_files::csv_column(rows, "unconverged_steps");
    const std::vector<double> steps = weft::test_files::csv_column(rows, "steps");
    return std::accumulate(unconverged.begin(), unconverged.end(), 0.0) /
           std::accumulate(steps.begin(), steps.end(), 0.0);
  };
  std::string fixed_output, adaptive_output;
  const double fixed = missed("fixed", "\"0.0416667 s\"", fixed_output);
  const double adaptive = missed("adaptive", "\"adaptive\"", adaptive_output);
  EXPECT_CONTAINS(fixed_output, "\"time_step\": \"adaptive\" shortens the steps");
  EXPECT_EQ(adaptive_output.find("shortens the steps"), std::string::npos) << adaptive_output;
  EXPECT_GT(fixed, 0.5);
  EXPECT_LT(adaptive, 0.1);
}

TEST_F(MessagesCli, ARayTracerOptionWithTheRasterRendererIsWarnedOf) {
  const std::string scene = write_scene("tiny.json", tiny_scene()).string();
  const auto raster = run_weft("run " + scene + " --frames 1 --samples 64 --out " +
                               (m_dir / "raster").string());
  EXPECT_EQ(raster.exit_code, 0) << raster.output;
  EXPECT_CONTAINS(raster.output, "warning: --samples 64: the raster renderer ignores it");
  const auto traced = run_weft("run " + scene + " --frames 1 --samples 4 --renderer raytrace --out " +
                               (m_dir / "raytrace").string());
  EXPECT_EQ(traced.exit_code, 0) << traced.output;
  EXPECT_EQ(traced.output.find("ignores"), std::string::npos) << traced.output;
}

// A limit shorter than a frame used to simulate nothing and report "settle time 0.00 s".
TEST_F(MessagesCli, UntilSettledShorterThanAFrameIsRefused) {
  const auto r = run_weft("measure " + write_scene("tiny.json", tiny_scene()).string() +
                          " --until-settled '1e-300 s' --out " + (m_dir / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "--until-settled: 1e-300 s is shorter than one frame of the scene");
}

// `cd DIR && weft run --resume checkpoint.weft` used to say "wrote 8 frames to  (": an empty
// folder name, and the interrupted run's frames counted as written.
TEST_F(MessagesCli, AResumeFromABareCheckpointNameNamesTheFolderAndTheFramesItWrote) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(run_weft("run " + write_scene("tiny.json", tiny_scene()).string() +
                     " --frames 8 --checkpoint-every 4 --out " + out.string()).exit_code, 0);
  const auto r = run_weft("run --resume checkpoint.weft", "cd " + out.string() + " &&");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "resuming from the checkpoint of frame 4 in .\n");
  EXPECT_CONTAINS(r.output, "wrote 4 frames to . (");
}

}  // namespace
