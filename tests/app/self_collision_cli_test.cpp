// A frame in which a self-colliding cloth still passes through itself is reported by
// `weft run` — a warning naming the frames, or, with simulation.self_collision.crossings set to
// "error", the run stops after writing that frame with the divergence exit code.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <string>

#include "tests/app/cli_test_support.h"

namespace weft::app::test {
namespace {

class SelfCollisionCli : public CliDirectoryTest {
 protected:
  SelfCollisionCli() : CliDirectoryTest("SelfCollisionCli") {}
};

// Seed 002's sphere drape at 32², dropped from 30 cm above the sphere: with the default
// neighbourhood its corner folds pass through themselves from about frame 15
// (tests/sim/self_collision_test.cpp, FoldsSharperThanAnEdgeHoldWithNeighbourhoodZero).
std::string dropped_drape(const std::string& self_collision) {
  return R"({
  "description": "the self-colliding sphere drape at 32 x 32, dropped from 30 cm above the sphere",
  "cloth": {"size": ["1 m", "1 m"], "resolution": [32, 32], "origin": ["-0.5 m", "-0.5 m", "1.15 m"],
    "material": {"density": "0.019 gf/cm^2", "stretch_warp": "1118.2 gf/cm",
      "stretch_weft": "759.5 gf/cm", "shear": "41.8 gf/cm", "bend_warp": "0.083 gf*cm",
      "bend_weft": "0.063 gf*cm"}},
  "obstacles": [{"sphere": {"center": ["0 m", "0 m", "0.6 m"], "radius": "25 cm"}},
    {"plane": {"point": [0, 0, 0], "normal": [0, 0, 1]}}],
  "simulation": {"air_damping": "2 1/s", "collision_friction": 0.5,
    "self_collision": )" + self_collision + R"(},
  "output": {"fps": 24, "frames": 24},
  "render": {"size": [64, 48]}
})";
}

int frames_in(const std::filesystem::path& dir) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    n += std::regex_match(entry.path().filename().string(), std::regex(R"(frame_\d{4}\.png)"));
  return n;
}

// The crossings come from the push-outs alone: the impact zones (on by default) leave
// none, so they are turned off to make some.
TEST_F(SelfCollisionCli, CrossingFramesAreWarnedOfByDefault) {
  const auto scene = write_scene("drape.json", dropped_drape(R"({"impact_zones": false})"));
  const CommandResult r = run_weft("run " + scene.string() + " --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "weft: warning: the cloth passes through itself despite self-collision in ");
  EXPECT_CONTAINS(r.output, " of 24 frames (");
  EXPECT_EQ(frames_in(m_dir / "out"), 24);
}

TEST_F(SelfCollisionCli, CrossingsAsErrorsStopAtTheFirstCrossingFrameKeepingIt) {
  const auto scene = write_scene("drape.json", dropped_drape(R"({"impact_zones": false, "crossings": "error"})"));
  const CommandResult r = run_weft("run " + scene.string() + " --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 3) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m,
                                std::regex(R"(error: frame (\d+): the cloth passes through itself \((\d+) edge)")))
      << r.output;
  const int frame = std::stoi(m[1]);
  EXPECT_GT(std::stoi(m[2]), 0);
  EXPECT_GT(frame, 1);
  EXPECT_LT(frame, 24);
  EXPECT_EQ(frames_in(m_dir / "out"), frame) << "frames 1.." << frame << " are kept, no later one";
  EXPECT_CONTAINS(r.output, "kept what frames 1.." + std::to_string(frame) + " wrote");
  // stats.csv: a header and one row per kept frame, the last with its crossings.
  std::ifstream csv(m_dir / "out" / "stats.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, frame + 1);
}

// The push-outs alone (impact zones off: they would hold any drape) with neighbourhood 0.
TEST_F(SelfCollisionCli, NeighbourhoodZeroHoldsTheDrapeWithoutAWarning) {
  const auto scene = write_scene(
      "drape.json",
      dropped_drape(R"({"neighbourhood": 0, "crossings": "error", "impact_zones": false})"));
  const CommandResult r = run_weft("run " + scene.string() + " --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("passes through itself"), std::string::npos) << r.output;
}

TEST_F(SelfCollisionCli, BadCrossingsAndNeighbourhoodValuesNameTheKey) {
  const auto bad = write_scene("bad.json", dropped_drape(R"({"crossings": "ignore"})"));
  CommandResult r = run_weft("run " + bad.string() + " --out " + (m_dir / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "simulation.self_collision.crossings");
  const auto far = write_scene("far.json", dropped_drape(R"({"neighbourhood": 5})"));
  r = run_weft("run " + far.string() + " --out " + (m_dir / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_CONTAINS(r.output, "simulation.self_collision.neighbourhood");
}

}  // namespace
}  // namespace weft::app::test
