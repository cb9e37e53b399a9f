// A cloth mesh file through the real `weft run` (issue 21 item 1): a triangle mesh with two
// corners painted red and pinned by colour writes its frames and stats.csv.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;

class MeshCli : public CliDirectoryTest {
 protected:
  MeshCli() : CliDirectoryTest("mesh_cli") {}
};

TEST_F(MeshCli, RunWritesFramesAndStatsForAColourPinnedTriangleMesh) {
  // A 0.4 m square of 5 × 5 vertices at z = 1 m cut into triangles; the corners (0, 0.4) and
  // (0.4, 0.4) red, the rest white.
  std::string obj;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      obj += "v " + std::to_string(0.1 * i) + " " + std::to_string(0.1 * j) + " 1" +
             ((j == 4 && (i == 0 || i == 4)) ? " 1 0 0\n" : " 1 1 1\n");
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 5) +
             "\nf " + std::to_string(a + 1) + " " + std::to_string(a + 6) + " " +
             std::to_string(a + 5) + "\n";
    }
  std::ofstream(m_dir / "square.obj") << obj;
  const fs::path scene = write_scene("scene.json", R"({
    "description": "a triangle-mesh square hung from its two red corners",
    "cloth": {"mesh": "square.obj", "pattern": "plane",
              "material": {"density": "0.2 kg/m^2", "stretch_warp": "200 N/m",
                           "stretch_weft": "150 N/m", "shear": "20 N/m",
                           "bend_warp": "2e-4 N*m", "bend_weft": "1e-4 N*m"},
              "pins": [{"color": [1, 0, 0]}]},
    "simulation": {"model": "baraff_witkin"},
    "output": {"fps": 10, "frames": 3},
    "render": {"size": [64, 48]}
  })");
  const fs::path out = m_dir / "out";
  const auto r = run_weft("run " + scene.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "25 vertices (square.obj)");
  for (const char* frame : {"frame_0001.png", "frame_0002.png", "frame_0003.png"}) {
    const weft::render::Image image = weft::render::read_image(out / frame);
    EXPECT_EQ(image.width(), 64) << frame;
    EXPECT_EQ(image.height(), 48) << frame;
  }
  std::ifstream stats(out / "stats.csv");
  std::string line;
  int rows = 0;
  ASSERT_TRUE(std::getline(stats, line)) << "no stats.csv";
  EXPECT_EQ(line.rfind("frame,time_s,", 0), 0u) << line;
  while (std::getline(stats, line)) rows += line.empty() ? 0 : 1;
  EXPECT_EQ(rows, 3);
}

}  // namespace
