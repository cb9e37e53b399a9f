// Frame selection through the real `weft run`: --start, --end, --every (with the range's last
// frame) and --last choose the frames rendered and written; every frame is still simulated and
// has its stats.csv row.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class FrameSelectionCli : public CliDirectoryTest {
 protected:
  FrameSelectionCli() : CliDirectoryTest("frame_selection_cli") {}
  // The frames (1..4 of the tiny scene) written by `weft run` with `options`.
  std::vector<int> frames_written(const std::string& options) {
    const fs::path out = m_dir / "out";
    const auto r = run_weft("run " + write_scene("tiny.json", tiny_scene()).string() + " " +
                            options + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::vector<int> frames;
    for (int k = 1; k <= 4; ++k)
      if (fs::exists(out / ("frame_000" + std::to_string(k) + ".png"))) frames.push_back(k);
    std::ifstream stats(out / "stats.csv");
    int lines = 0;
    for (std::string line; std::getline(stats, line);) ++lines;
    EXPECT_EQ(lines, 5) << "a header and a row for each simulated frame";
    EXPECT_CONTAINS(r.output, "wrote " + std::to_string(frames.size()) + " frame");
    return frames;
  }
};

TEST_F(FrameSelectionCli, StartEndEveryAndLastChooseTheFrames) {
  EXPECT_EQ(frames_written(""), (std::vector<int>{1, 2, 3, 4}));
  // --every N from --start, and the last frame of the range too (the cloth at rest, which
  // --every 24 over 96 frames used to leave out).
  EXPECT_EQ(frames_written("--every 2"), (std::vector<int>{1, 3, 4}));
  EXPECT_EQ(frames_written("--every 3"), (std::vector<int>{1, 4}));
  EXPECT_EQ(frames_written("--start 2 --end 3"), (std::vector<int>{2, 3}));
  EXPECT_EQ(frames_written("--start 2 --every 2"), (std::vector<int>{2, 4}));
  EXPECT_EQ(frames_written("--end 3 --every 4"), (std::vector<int>{1, 3}));
  EXPECT_EQ(frames_written("--last"), (std::vector<int>{4}));
}

TEST_F(FrameSelectionCli, ASelectionOutsideTheRunIsAnError) {
  const std::string scene = write_scene("tiny.json", tiny_scene()).string();
  const auto late = run_weft("run " + scene + " --start 9 --out " + (m_dir / "a").string());
  EXPECT_EQ(late.exit_code, 1) << late.output;
  EXPECT_CONTAINS(late.output, "--start/--end: expected 1 <= start <= end <= 4");
  EXPECT_FALSE(fs::exists(m_dir / "a"));
  const auto both = run_weft("run " + scene + " --last --every 2");
  EXPECT_EQ(both.exit_code, 1) << both.output;
  const auto zero = run_weft("run " + scene + " --every 0");
  EXPECT_EQ(zero.exit_code, 1) << zero.output;
  EXPECT_CONTAINS(zero.output, "--every");
}

}  // namespace
