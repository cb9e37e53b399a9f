// The ground and the camera through the real `weft run`: the drawn ground stops the cloth unless
// the scene says render.ground.collider: false, and a scene without a camera is framed so that the
// cloth stays in view over the whole run, simulated once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/io/mesh_file.h"
#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::file_bytes;
using weft::app::test::run_weft;

// A free 20 cm sheet 30 cm up (or `origin`), no obstacles and no camera: 1 s at 12 fps.
std::string falling_sheet(const std::string& origin, const std::string& ground) {
  return R"({
  "description": "a minimal scene: a free sheet falling onto the drawn ground",
  "cloth": {"size": ["20 cm", "20 cm"], "resolution": [9, 9], "origin": )" + origin + R"(},
  "output": {"fps": 12, "frames": 12},
  "render": {"size": [160, 120])" + ground + R"(}
})";
}

// Pixels unlike the top-left one (the background, in a scene without a ground): the cloth's.
int cloth_pixels(const fs::path& png) {
  const weft::render::Image image = weft::render::read_image(png);
  const weft::render::Rgb8 background = image.at(0, 0);
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const weft::render::Rgb8 p = image.at(x, y);
      n += std::max({std::abs(p.r - background.r), std::abs(p.g - background.g),
                     std::abs(p.b - background.b)}) > 30;
    }
  return n;
}

// stats.csv's rows (the header aside).
int stats_rows(const fs::path& stats) {
  std::ifstream in(stats);
  int rows = -1;
  for (std::string line; std::getline(in, line);) ++rows;
  return rows;
}

class GroundCameraCli : public CliDirectoryTest {
 protected:
  GroundCameraCli() : CliDirectoryTest("ground_camera_cli") {}
  // Runs the scene; returns the lowest height of the last frame's cloth (exported z-up).
  double lowest_z(const std::string& text, const std::string& name) {
    const fs::path out = m_dir / name;
    const auto r = run_weft("run " + write_scene(name + ".json", text).string() +
                            " --export-meshes ply --up z --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("framing the cloth") != std::string::npos,
              text.find("camera") == std::string::npos) << r.output;
    return weft::app::load_triangle_mesh(out / "mesh_0012.ply").vertices.col(2).minCoeff();
  }
};

TEST_F(GroundCameraCli, TheDrawnGroundStopsTheCloth) {
  const double on_ground = lowest_z(falling_sheet("[-0.1, -0.1, 0.3]", ""), "ground");
  EXPECT_GT(on_ground, -1e-3);  // resting on z = 0 (within the collision thickness above it)
  EXPECT_LT(on_ground, 0.02);
  // Free fall for 1 s from 0.3 m: below −4 m without the collider.
  const double through = lowest_z(
      falling_sheet("[-0.1, -0.1, 0.3]", R"(, "ground": {"collider": false})"), "no_collider");
  EXPECT_LT(through, -3.0);
}

TEST_F(GroundCameraCli, WithoutACameraTheClothStaysInView) {
  // 5 m from the default camera's target (0, 0, 0.5), 2 m up, falling 4 m in the run (no ground).
  const std::string far = falling_sheet("[5, 5, 2]", R"(, "ground": false)");
  lowest_z(far, "framed");
  for (const char* frame : {"frame_0001.png", "frame_0006.png", "frame_0012.png"})
    EXPECT_GT(cloth_pixels(m_dir / "framed" / frame), 3) << frame;  // edge-on: a few pixels
  // The default camera itself, given explicitly, sees none of it.
  std::string fixed = far;
  fixed.insert(fixed.find(R"("ground": false)"), R"("camera": {}, )");
  lowest_z(fixed, "fixed");
  for (const char* frame : {"frame_0001.png", "frame_0012.png"})
    EXPECT_EQ(cloth_pixels(m_dir / "fixed" / frame), 0) << frame;
}

// The camera of a scene without one frames the cloth over the whole run, which weft run learns
// while simulating: it keeps each frame's state, and draws the frames from them when the
// simulation ends (the same bits as framing from a pass of its own: CheckpointCli's
// ARunWithoutACameraResumedAfterAKillGivesTheSameBits; the time saved: docs/run.md).
TEST_F(GroundCameraCli, ARunWithoutACameraDrawsFromTheStatesItKept) {
  std::string text = file_bytes(fs::path(WEFT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  const std::size_t camera = text.find(R"("camera": {)");
  ASSERT_NE(camera, std::string::npos);
  text.erase(camera, text.find("},", camera) + 2 - camera);
  const std::string scene = write_scene("no_camera.json", text).string();
  const fs::path out = m_dir / "run";
  const auto r = run_weft("run " + scene + " --frames 36 --size 64x48 --last --threads 1 --out " +
                          out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "framing the cloth's bounding box over the run");
  EXPECT_CONTAINS(r.output, "the frames are drawn when the simulation ends");
  EXPECT_EQ(stats_rows(out / "stats.csv"), 36);
  EXPECT_TRUE(fs::exists(out / "frame_0036.png"));
  EXPECT_FALSE(fs::exists(out / "frame_0035.png")) << "--last draws the last frame only";
  EXPECT_FALSE(fs::exists(out / "state_0000.npy")) << "the kept states are removed";
}

}  // namespace
