// Checkpoints through the real `weft run`: a run with --checkpoint-every that is killed
// (SIGKILL) after frame 30 and resumed with --resume from its checkpoint of frame 24 writes the
// same frames (PNG bytes) and stats.csv rows (minus the wall-time columns) as a run that never
// stopped and never wrote a checkpoint; checkpoints of another scene or build, or damaged
// ones, are refused with an error naming the file. A run without a camera, which draws its
// frames from its kept states when the simulation ends, resumes to the same bits too, whether
// those states are still in the folder or not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

using weft::app::test::file_bytes;
// stats.csv's lines without the wall-time columns (sim_ms, render_ms, solve_ms).
std::vector<std::string> stats_without_wall_times(const fs::path& path) {
  std::vector<std::string> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream cells_in(line);
    for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(cell);
    std::string kept;
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (c != 2 && c != 3 && c != 14) kept += cells[c] + ",";
    rows.push_back(kept);
  }
  return rows;
}

class CheckpointCli : public CliDirectoryTest {
 protected:
  CheckpointCli() : CliDirectoryTest("checkpoint_cli") {}

  // `weft run ARGS --out DIR` killed with SIGKILL as soon as DIR/frame_00NN.png (or another
  // numbered file, `prefix`_00NN.`extension`) exists; true when the kill came before the run
  // ended by itself.
  bool run_and_kill(const std::string& args, const fs::path& out, int kill_after,
                    const char* prefix = "frame", const char* extension = "png") {
    char frame[32];
    std::snprintf(frame, sizeof frame, "%s_%04d.%s", prefix, kill_after, extension);
    const fs::path script = m_dir / "run_and_kill.sh";
    std::ofstream(script) << WEFT_EXECUTABLE << " run " << args << " --out " << out.string()
                          << " >/dev/null 2>&1 &\npid=$!\nwhile kill -0 $pid 2>/dev/null && [ ! -e "
                          << (out / frame).string() << " ]; do sleep 0.002; done\n"
                          << "kill -9 $pid 2>/dev/null\nwait $pid 2>/dev/null\ntest $? -eq 137\n";
    return std::system(("sh " + script.string() + " 2>/dev/null").c_str()) == 0;
  }

  // Runs `args` for 48 frames uninterrupted, and with checkpoints every 24 frames killed after
  // frame 30 and resumed: the frames and stats rows must be the same.
  void expect_resume_gives_the_same_bits(const std::string& args) {
    const fs::path whole = m_dir / "whole", cut = m_dir / "cut";
    const auto reference = run_weft("run " + args + " --frames 48 --out " + whole.string());
    ASSERT_EQ(reference.exit_code, 0) << reference.output;
    const bool killed = run_and_kill(args + " --frames 48 --checkpoint-every 24", cut, 30);
    ASSERT_TRUE(fs::exists(cut / "checkpoint.weft"));
    const std::size_t rows_at_kill = stats_without_wall_times(cut / "stats.csv").size() - 1;
    std::printf("killed: %s, after frame %zu of 48\n", killed ? "yes" : "no (the run ended first)",
                rows_at_kill);
    EXPECT_GE(rows_at_kill, 29u) << "frame 30's PNG is written just before its stats.csv row";
    const auto resumed = run_weft("run --resume " + cut.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_CONTAINS(resumed.output, "resuming from the checkpoint of frame 24");
    for (int k = 1; k <= 48; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04d.png", k);
      ASSERT_TRUE(fs::exists(cut / name)) << name;
      EXPECT_TRUE(file_bytes(whole / name) == file_bytes(cut / name)) << name << " differs";
    }
    EXPECT_EQ(stats_without_wall_times(whole / "stats.csv"),
              stats_without_wall_times(cut / "stats.csv"));
    EXPECT_EQ(stats_without_wall_times(cut / "stats.csv").size(), 49u);
  }
};

TEST_F(CheckpointCli, TheDefaultSceneResumedAfterAKillGivesTheSameBits) {
  expect_resume_gives_the_same_bits("--size 96x72 --set cloth.resolution=[21,21]");
}

// Implicit Euler by conjugate gradients (warm start), fast projection with carried tension,
// friction on a sphere and the ground, self-collision's side memory.
TEST_F(CheckpointCli, AnInextensibleSelfCollidingDrapeResumedAfterAKillGivesTheSameBits) {
  const std::string scene = std::string(WEFT_SOURCE_DIR) + "/assets/scenes/sphere_drape_inextensible.json";
  expect_resume_gives_the_same_bits(scene + " --size 96x72 --set cloth.resolution=[17,17] --set "
                                            "'simulation.self_collision={\"thickness\":\"1 cm\"}'");
  // The run has self-contacts to remember: max_self_contacts, stats.csv's last column.
  long most_contacts = 0;
  for (const std::string& row : stats_without_wall_times(m_dir / "whole" / "stats.csv")) {
    const std::string cells = row.substr(0, row.size() - 1);
    const std::string last = cells.substr(cells.rfind(',') + 1);
    if (!last.empty() && std::isdigit(static_cast<unsigned char>(last[0])))
      most_contacts = std::max(most_contacts, std::stol(last));
  }
  EXPECT_GT(most_contacts, 0);
}

// Central difference (its last step), moving pins (their paths), a checkpoint of a resumed
// run, and a run resumed twice.
TEST_F(CheckpointCli, ACentralDifferenceRunResumedTwiceGivesTheSameBits) {
  std::string text = tiny_scene("", R"(, "simulation": {"integrator": "central_difference"})");
  const std::string pin = R"({"corner": "u0v1")";
  text.replace(text.find(pin), pin.size(),
               pin + R"(, "path": [{"time": "0 s", "offset": [0, 0, 0]}, {"time": "1 s", "offset": ["5 cm", 0, 0]}])");
  const std::string scene = write_scene("tiny.json", text).string();
  const fs::path whole = m_dir / "whole", cut = m_dir / "cut";
  ASSERT_EQ(run_weft("run " + scene + " --frames 24 --out " + whole.string()).exit_code, 0);
  const auto first = run_weft("run " + scene + " --frames 24 --checkpoint-every 8 --out " + cut.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  for (int resumes = 0; resumes < 2; ++resumes) {
    const auto r = run_weft("run --resume " + cut.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_CONTAINS(r.output, "resuming from the checkpoint of frame 16");
  }
  for (int k = 1; k <= 24; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    EXPECT_TRUE(file_bytes(whole / name) == file_bytes(cut / name)) << name << " differs";
  }
  EXPECT_EQ(stats_without_wall_times(whole / "stats.csv"), stats_without_wall_times(cut / "stats.csv"));
}

// Without a camera the frames are drawn when the simulation ends, from the states kept in the
// folder meanwhile; the camera frames the cloth over frames 0..48. Killed after frame 30's state
// (no frame drawn yet), the run resumed from frame 24 takes frames 0..24's box from the kept
// states and draws all 48 frames; resumed again from the same checkpoint once those states are
// gone (the run removed them after drawing), it simulates frames 1..24 again for the box. Both
// give the frames of the run that never stopped.
TEST_F(CheckpointCli, ARunWithoutACameraResumedAfterAKillGivesTheSameBits) {
  std::string text = tiny_scene();
  const std::string camera = R"(, "camera": {"eye": [0.6, -0.5, 0.6], "target": [0, 0.1, 0.4]})";
  text.erase(text.find(camera), camera.size());
  const std::string scene = write_scene("no_camera.json", text).string();
  const fs::path whole = m_dir / "whole", cut = m_dir / "cut";
  const auto reference = run_weft("run " + scene + " --frames 48 --mask --out " + whole.string());
  ASSERT_EQ(reference.exit_code, 0) << reference.output;
  EXPECT_CONTAINS(reference.output, "framing the cloth's bounding box");
  EXPECT_FALSE(fs::exists(whole / "state_0000.npy")) << "the kept states are removed";
  EXPECT_FALSE(fs::exists(whole / "state_0048.npy"));

  const bool killed =
      run_and_kill(scene + " --frames 48 --mask --checkpoint-every 24", cut, 30, "state", "npy");
  ASSERT_TRUE(fs::exists(cut / "checkpoint.weft"));
  std::printf("killed: %s\n", killed ? "yes" : "no (the run ended first)");
  if (killed) {
    EXPECT_FALSE(fs::exists(cut / "frame_0001.png")) << "no frame drawn before the end";
  }
  // Frames first..48 (and their masks) as the uninterrupted run's; stats.csv the same.
  const auto expect_whole_run = [&](int first, const std::string& when) {
    for (int k = first; k <= 48; ++k) {
      char frame[32], mask[32];
      std::snprintf(frame, sizeof frame, "frame_%04d.png", k);
      std::snprintf(mask, sizeof mask, "mask_%04d.png", k);
      ASSERT_TRUE(fs::exists(cut / frame)) << frame << ", " << when;
      EXPECT_TRUE(file_bytes(whole / frame) == file_bytes(cut / frame)) << frame << " differs, " << when;
      EXPECT_TRUE(file_bytes(whole / mask) == file_bytes(cut / mask)) << mask << " differs, " << when;
    }
    EXPECT_EQ(stats_without_wall_times(whole / "stats.csv"),
              stats_without_wall_times(cut / "stats.csv")) << when;
    EXPECT_FALSE(fs::exists(cut / "state_0000.npy")) << when;
  };

  const auto resumed = run_weft("run --resume " + cut.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_CONTAINS(resumed.output, "resuming from the checkpoint of frame 24");
  EXPECT_EQ(resumed.output.find("simulating frames 1..24 again"), std::string::npos)
      << "the kept states give frames 0..24's box\n" << resumed.output;
  expect_whole_run(1, "resumed with the kept states");

  for (int k = 1; k <= 48; ++k) {
    char frame[32];
    std::snprintf(frame, sizeof frame, "frame_%04d.png", k);
    fs::remove(cut / frame);
  }
  const auto again = run_weft("run --resume " + cut.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_CONTAINS(again.output, "simulating frames 1..24 again for the camera");
  EXPECT_FALSE(fs::exists(cut / "frame_0024.png"))
      << "frames 1..24 were drawn by the run that removed their states";
  expect_whole_run(25, "resumed again without the states");
}

TEST_F(CheckpointCli, CheckpointsOfAnotherSceneOrBuildOrDamagedOnesAreRefused) {
  const std::string scene = write_scene("tiny.json", tiny_scene()).string();
  const fs::path cut = m_dir / "cut";
  ASSERT_EQ(run_weft("run " + scene + " --frames 8 --checkpoint-every 4 --out " + cut.string()).exit_code, 0);
  const fs::path file = cut / "checkpoint.weft";
  const std::string good = file_bytes(file);

  const auto other_scene = run_weft("run " + scene + " --set cloth.resolution=[7,7] --resume " + cut.string());
  EXPECT_EQ(other_scene.exit_code, 1) << other_scene.output;
  EXPECT_CONTAINS(other_scene.output, "the checkpoint belongs to another scene");
  const auto same_scene = run_weft("run " + scene + " --frames 8 --resume " + cut.string());
  EXPECT_EQ(same_scene.exit_code, 0) << same_scene.output;

  std::string other_build = good;
  other_build[std::string("weft checkpoint 3\n").size()] ^= 1;  // the build hash's first byte
  std::ofstream(file, std::ios::binary) << other_build;
  const auto build = run_weft("run --resume " + cut.string());
  EXPECT_EQ(build.exit_code, 1) << build.output;
  EXPECT_CONTAINS(build.output, file.string() + ": written by another build of weft");

  // Format version 1 (before remeshed meshes were saved) is refused by its version.
  std::string version_1 = good;
  version_1.replace(0, std::string("weft checkpoint 3").size(), "weft checkpoint 1");
  std::ofstream(file, std::ios::binary) << version_1;
  const auto old_format = run_weft("run --resume " + cut.string());
  EXPECT_EQ(old_format.exit_code, 1) << old_format.output;
  EXPECT_CONTAINS(old_format.output, file.string() + ": a weft checkpoint of format version 1; "
                                     "this weft reads version 3 only");

  std::ofstream(file, std::ios::binary) << good.substr(0, good.size() - 100);
  const auto truncated = run_weft("run --resume " + cut.string());
  EXPECT_EQ(truncated.exit_code, 1) << truncated.output;
  EXPECT_CONTAINS(truncated.output, "a damaged checkpoint");

  std::ofstream(file, std::ios::binary) << "not a checkpoint";
  const auto junk = run_weft("run --resume " + cut.string());
  EXPECT_EQ(junk.exit_code, 1) << junk.output;
  EXPECT_CONTAINS(junk.output, "not a weft checkpoint");

  const auto missing = run_weft("run --resume " + (m_dir / "nowhere").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_CONTAINS(missing.output, "cannot read a checkpoint");

  // A new run in the folder removes the earlier run's checkpoint: --resume cannot mix runs.
  ASSERT_EQ(run_weft("run " + scene + " --frames 8 --out " + cut.string()).exit_code, 0);
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
