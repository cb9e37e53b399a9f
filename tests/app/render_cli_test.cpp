// Render-only runs through the real commands: `weft render` draws frames from the states
// `weft run --save-states` wrote with the same bytes as the frames weft run writes — a chosen
// range and step, the automatic camera (framed from the states), a moving obstacle, masks, the
// ray tracer — and a 12-frame ray-traced sequence drawn as 4 frame ranges (array tasks) equals
// the single run's frames; bad ranges, missing states and simulation keys are refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;

using weft::app::test::file_bytes;
std::string numbered(const char* prefix, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "%s_%04d.png", prefix, k);
  return name;
}

// A 9×9 cloth pinned at two corners over a sphere that moves under it; no camera (weft frames
// the cloth over the run).
const char* const kScene = R"({
  "description": "a cloth over a moving sphere, no camera",
  "cloth": {"size": ["20 cm", "20 cm"], "resolution": [9, 9], "origin": [-0.1, 0, 0.5],
            "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
  "obstacles": [{"sphere": {"center": [0, 0.1, 0.42], "radius": "4 cm"},
                 "motion": [{"time": "0 s"}, {"time": "0.5 s", "translate": ["5 cm", 0, 0]}]}],
  "output": {"fps": 24, "frames": 12},
  "render": {"size": [96, 64]}
})";

class RenderCli : public CliDirectoryTest {
 protected:
  RenderCli() : CliDirectoryTest("render_cli") {}
  fs::path run(const std::string& options) {
    const fs::path out = m_dir / "run";
    const auto r = run_weft("run " + write_scene("moving.json", kScene).string() +
                            " --save-states " + options + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out / "state_0000.npy"));
    EXPECT_TRUE(fs::exists(out / "state_0012.npy"));
    return out;
  }
};

TEST_F(RenderCli, FramesDrawnFromSavedStatesAreTheBytesWeftRunWrote) {
  const fs::path states = run("--mask");
  const fs::path out = m_dir / "render";
  const auto r = run_weft("render " + states.string() + " --frames 3-10 --every 3 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "rendered 4 frames (3–10 every 3)");
  for (int k = 1; k <= 12; ++k) {
    const bool selected = k == 3 || k == 6 || k == 9 || k == 10;  // and the range's last
    EXPECT_EQ(fs::exists(out / numbered("frame", k)), selected) << k;
    if (!selected) continue;
    EXPECT_TRUE(file_bytes(states / numbered("frame", k)) == file_bytes(out / numbered("frame", k))) << k;
    EXPECT_TRUE(file_bytes(states / numbered("mask", k)) == file_bytes(out / numbered("mask", k))) << k;
  }
  // Other render settings draw other frames from the same states.
  const auto bigger = run_weft("render " + states.string() + " --frames 3 --size 128x96 --out " +
                               (m_dir / "bigger").string());
  ASSERT_EQ(bigger.exit_code, 0) << bigger.output;
  EXPECT_FALSE(file_bytes(states / numbered("frame", 3)) == file_bytes(m_dir / "bigger" / numbered("frame", 3)));
}

TEST_F(RenderCli, ARayTracedSequenceDrawnAsFourFrameRangesEqualsTheRunsFrames) {
  const fs::path states = run("--renderer raytrace --samples 2");
  const fs::path out = m_dir / "tasks";
  for (const char* range : {"1-3", "4-6", "7-9", "10-12"}) {
    const auto r = run_weft("render " + states.string() + " --frames " + range +
                            " --renderer raytrace --samples 2 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  for (int k = 1; k <= 12; ++k)
    EXPECT_TRUE(file_bytes(states / numbered("frame", k)) == file_bytes(out / numbered("frame", k))) << k;
}

// The script weft render --slurm writes is a bash script: run with SLURM_ARRAY_TASK_ID = 1..4,
// as Slurm runs its array tasks (numbered from 1, as sweep's and gallery's), it draws the run's
// frames; 0 and 5 are no task of it.
TEST_F(RenderCli, ASlurmArrayScriptOfFourTasksDrawsTheRunsFrames) {
  const fs::path states = run("--renderer raytrace --samples 2");
  const fs::path out = m_dir / "slurm_out";
  const auto r = run_weft("render " + states.string() +
                          " --renderer raytrace --samples 2 --slurm --tasks 4 --dry-run --out " +
                          out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "4 array tasks for 12 frames (not submitted: --dry-run)");
  EXPECT_CONTAINS(r.output, "#SBATCH --array=1-4");
  const fs::path script = out / "slurm" / "render.sbatch";
  ASSERT_TRUE(fs::exists(script));
  EXPECT_CONTAINS(file_bytes(script), "'--frames' '10-12'");
  EXPECT_FALSE(fs::exists(out / numbered("frame", 1))) << "--dry-run draws nothing";
  for (int task = 1; task <= 4; ++task)
    EXPECT_EQ(std::system(("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " +
                           script.string() + " >/dev/null 2>&1").c_str()), 0) << task;
  for (int k = 1; k <= 12; ++k)
    EXPECT_TRUE(file_bytes(states / numbered("frame", k)) == file_bytes(out / numbered("frame", k))) << k;
  for (const char* task : {"0", "5"})
    EXPECT_NE(std::system(("SLURM_ARRAY_TASK_ID=" + std::string(task) + " bash " + script.string() +
                           " 2>/dev/null").c_str()), 0) << task;
}

// Without --out, weft render draws into DIR/render: DIR's own frames are the run's, which a
// render with other settings used to overwrite.
TEST_F(RenderCli, WithoutOutTheFramesGoToARenderFolderAndTheRunsStay) {
  const fs::path states = run("");
  const std::string before = file_bytes(states / numbered("frame", 2));
  const auto r = run_weft("render " + states.string() + " --frames 2 --size 48x32");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "into " + (states / "render").string());
  EXPECT_EQ(file_bytes(states / numbered("frame", 2)), before) << "the run's frame kept";
  ASSERT_TRUE(fs::exists(states / "render" / numbered("frame", 2)));
  EXPECT_NE(file_bytes(states / "render" / numbered("frame", 2)), before) << "48x32, not 96x64";
}

TEST_F(RenderCli, BadRangesMissingStatesAndSimulationKeysAreRefused) {
  const fs::path states = run("");
  const auto range = run_weft("render " + states.string() + " --frames 5-13");
  EXPECT_EQ(range.exit_code, 1) << range.output;
  EXPECT_CONTAINS(range.output, "--frames: expected A-B or A with 1 <= A <= B <= 12");
  const auto key = run_weft("render " + states.string() + " --set simulation.time_step=1ms");
  EXPECT_EQ(key.exit_code, 1) << key.output;
  EXPECT_CONTAINS(key.output, "only render.* keys");
  fs::remove(states / "state_0007.npy");
  const auto missing = run_weft("render " + states.string() + " --frames 7 --out " + (m_dir / "m").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_CONTAINS(missing.output, (states / "state_0007.npy").string() + ": no such state");
  EXPECT_FALSE(fs::exists(m_dir / "m" / numbered("frame", 7)));
}

}  // namespace
