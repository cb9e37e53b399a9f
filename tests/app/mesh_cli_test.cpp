// A cloth mesh file through the real `weft run`: a triangle mesh with two
// corners painted red and pinned by colour writes its frames and stats.csv; remeshed as it runs
// (simulation.remesh), each frame's vertex count is in stats.csv, a checkpoint holds
// the remeshed mesh (a resumed run gives the same bits), saved states come with their meshes
// (weft render draws them), and a point cache, which keeps one mesh for the whole run, is an
// error.
#include <gtest/gtest.h>

#include <algorithm>
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

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;

// A 0.4 m square of 5 × 5 vertices at z = 1 m cut into triangles; the corners (0, 0.4) and
// (0.4, 0.4) red, the rest white.
std::string red_cornered_square_obj() {
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
  return obj;
}

// The square of red_cornered_square_obj() as square.obj, hung from its red corners, on the
// Baraff–Witkin model's material; `simulation`, `output` and `render` are those blocks.
std::string hung_square_scene(const std::string& simulation, const std::string& output,
                              const std::string& render) {
  return R"({
    "description": "a triangle-mesh square hung from its two red corners",
    "cloth": {"mesh": "square.obj", "pattern": "plane",
              "material": {"density": "0.2 kg/m^2", "stretch_warp": "200 N/m",
                           "stretch_weft": "150 N/m", "shear": "20 N/m",
                           "bend_warp": "2e-4 N*m", "bend_weft": "1e-4 N*m"},
              "pins": [{"color": [1, 0, 0]}]},
    "simulation": )" + simulation + R"(,
    "output": )" + output + R"(,
    "render": )" + render + "\n}";
}

class MeshCli : public CliDirectoryTest {
 protected:
  MeshCli() : CliDirectoryTest("mesh_cli") {}
};

TEST_F(MeshCli, RunWritesFramesAndStatsForAColourPinnedTriangleMesh) {
  std::ofstream(m_dir / "square.obj") << red_cornered_square_obj();
  const fs::path scene = write_scene(
      "scene.json", hung_square_scene(R"({"model": "baraff_witkin"})", R"({"fps": 10, "frames": 3})",
                                      R"({"size": [64, 48]})"));
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

// stats.csv's column `name`, one value per frame.
std::vector<double> stats_column(const fs::path& csv, const std::string& name) {
  const auto rows = weft::test_files::read_csv(csv);
  std::vector<double> values;
  if (rows.empty()) return values;
  const auto column = std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin();
  for (std::size_t r = 1; r < rows.size(); ++r)
    values.push_back(std::stod(rows[r].at(static_cast<std::size_t>(column))));
  return values;
}

TEST_F(MeshCli, ARemeshedRunWritesEachFramesMeshAndVertexCount) {
  std::ofstream(m_dir / "square.obj") << red_cornered_square_obj();
  const fs::path scene = write_scene(
      "scene.json",
      hung_square_scene(R"({"model": "baraff_witkin", "integrator": "implicit_euler",
                            "remesh": {"every": 6, "c": "1 mm", "h_min": "1 cm",
                                       "h_max": "4 cm"}})",
                        R"({"fps": 20, "frames": 4})", R"({"size": [64, 48], "wireframe": true})"));
  const fs::path out = m_dir / "remeshed";
  const auto r = run_weft("run " + scene.string() + " --out " + out.string() +
                          " --export-meshes obj --explain");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "remesh: every 6 steps");
  // 6 steps of 1/120 s per frame: a remesh at the end of each.
  EXPECT_EQ(stats_column(out / "stats.csv", "remeshes"), (std::vector<double>{1, 1, 1, 1}));
  // Remeshed every 6 steps, not by the indicator: no coarsening criterion at work.
  EXPECT_EQ(stats_column(out / "stats.csv", "coarsenings"), (std::vector<double>{0, 0, 0, 0}));
  EXPECT_EQ(stats_column(out / "stats.csv", "remesh_excess"), (std::vector<double>{0, 0, 0, 0}));
  const std::vector<double> vertices = stats_column(out / "stats.csv", "vertices");
  ASSERT_EQ(vertices.size(), 4u);
  EXPECT_NE(vertices.front(), 25.0) << "the first frame's mesh is the remeshed one";
  // Each exported mesh is its frame's: as many vertices as stats.csv says.
  for (int k = 1; k <= 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "mesh_%04d.obj", k);
    std::ifstream obj(out / name);
    int count = 0;
    for (std::string line; std::getline(obj, line);) count += line.rfind("v ", 0) == 0;
    EXPECT_EQ(count, vertices[static_cast<std::size_t>(k - 1)]) << name;
  }
  // A point cache holds one mesh's vertices.
  const auto refused = run_weft("run " + scene.string() + " --out " +
                                (m_dir / "refused").string() + " --export-cache pc2");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_CONTAINS(refused.output, "--export-cache: not with simulation.remesh");
}

// The hung square remeshed after every frame (6 steps of 1/120 s at 20 fps), 8 frames, drawn
// with its mesh lines: the image depends on the mesh.
// With `camera`, a fixed camera; without, weft frames the cloth over the run (simulating it
// once more for that).
std::string remeshed_square_scene(bool camera) {
  return hung_square_scene(R"({"model": "baraff_witkin", "integrator": "implicit_euler",
                               "remesh": {"every": 6, "c": "1 mm", "h_min": "3 cm",
                                          "h_max": "6 cm"}})",
                           R"({"fps": 20, "frames": 8})",
                           std::string(R"({"size": [64, 48], "wireframe": true)") +
                               (camera ? R"(, "camera": {"eye": [0.2, -0.9, 0.8],
                                            "target": [0.2, 0.3, 0.75], "up": [0, 0, 1]}})"
                                       : "}"));
}

std::string remeshed_output_name(const char* prefix, int k, const char* extension) {
  char name[40];
  std::snprintf(name, sizeof name, "%s_%04d.%s", prefix, k, extension);
  return name;
}

// A remeshed run with --checkpoint-every 3, its frames after the checkpoint of frame 6 deleted
// and resumed: the checkpoint holds the remeshed mesh, and the resumed run (remeshed in each of
// its 2 frames) writes the same PNG bytes and stats.csv rows as the run that never stopped.
TEST_F(MeshCli, ARemeshedRunResumedFromItsCheckpointGivesTheSameBits) {
  std::ofstream(m_dir / "square.obj") << red_cornered_square_obj();
  const fs::path scene = write_scene("scene.json", remeshed_square_scene(true));
  const fs::path whole = m_dir / "whole", cut = m_dir / "cut";
  const auto a = run_weft("run " + scene.string() + " --out " + whole.string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const auto b = run_weft("run " + scene.string() + " --checkpoint-every 3 --out " + cut.string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  ASSERT_TRUE(fs::exists(cut / "checkpoint.weft"));
  for (int k = 7; k <= 8; ++k) fs::remove(cut / remeshed_output_name("frame", k, "png"));
  // Resumed with --save-states, which the interrupted run did not give: the states after the
  // checkpoint come with their mesh, and weft render draws them as weft run did.
  const auto resumed = run_weft("run --resume " + cut.string() + " --save-states");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_CONTAINS(resumed.output, "resuming from the checkpoint of frame 6");
  EXPECT_TRUE(fs::exists(cut / "cloth_mesh_0007.weft"));
  const auto drawn = run_weft("render " + cut.string() + " --scene " + scene.string() +
                              " --frames 7-8 --out " + (m_dir / "drawn").string());
  ASSERT_EQ(drawn.exit_code, 0) << drawn.output;
  for (int k = 7; k <= 8; ++k)
    EXPECT_TRUE(weft::app::test::file_bytes(whole / remeshed_output_name("frame", k, "png")) ==
                weft::app::test::file_bytes(m_dir / "drawn" / remeshed_output_name("frame", k, "png")))
        << "frame " << k << " drawn from the resumed run's states";
  for (int k = 1; k <= 8; ++k) {
    const std::string name = remeshed_output_name("frame", k, "png");
    ASSERT_TRUE(fs::exists(cut / name)) << name;
    EXPECT_TRUE(weft::app::test::file_bytes(whole / name) ==
                weft::app::test::file_bytes(cut / name))
        << name << " differs";
  }
  const std::vector<double> vertices = stats_column(whole / "stats.csv", "vertices");
  ASSERT_EQ(vertices.size(), 8u);
  EXPECT_EQ(stats_column(cut / "stats.csv", "vertices"), vertices);
  EXPECT_EQ(stats_column(cut / "stats.csv", "remeshes"), stats_column(whole / "stats.csv", "remeshes"));
  EXPECT_EQ(stats_column(cut / "stats.csv", "max_strain"),
            stats_column(whole / "stats.csv", "max_strain"));
  EXPECT_EQ(stats_column(cut / "stats.csv", "kinetic_energy_J"),
            stats_column(whole / "stats.csv", "kinetic_energy_J"));
  EXPECT_NE(vertices[5], 25.0) << "the checkpoint's mesh is not the scene's";
  EXPECT_EQ(stats_column(whole / "stats.csv", "remeshes"), std::vector<double>(8, 1.0))
      << "remeshed in every frame, after the checkpoint too";
}

// --save-states of a remeshed run writes each frame's mesh where it changed (cloth_mesh_0000.weft
// and one per remeshed frame); weft render draws every frame on its own mesh, framed by the
// automatic camera from all the states, with the bytes weft run wrote.
TEST_F(MeshCli, ARemeshedRunsSavedStatesAreDrawnOnTheirOwnMeshes) {
  std::ofstream(m_dir / "square.obj") << red_cornered_square_obj();
  const fs::path scene = write_scene("scene.json", remeshed_square_scene(false));
  const fs::path run = m_dir / "run", drawn = m_dir / "drawn";
  const auto r = run_weft("run " + scene.string() + " --save-states --out " + run.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(run / "cloth_mesh_0000.weft"));
  EXPECT_TRUE(fs::exists(run / "cloth_mesh_0008.weft")) << "remeshed in every frame";
  // The scene names its mesh file by a relative path: --scene gives the original.
  const std::string render = "render " + run.string() + " --scene " + scene.string();
  const auto d = run_weft(render + " --out " + drawn.string());
  ASSERT_EQ(d.exit_code, 0) << d.output;
  for (int k = 1; k <= 8; ++k) {
    const std::string name = remeshed_output_name("frame", k, "png");
    EXPECT_TRUE(weft::app::test::file_bytes(run / name) ==
                weft::app::test::file_bytes(drawn / name))
        << name << " differs";
  }
  // A range drawn alone finds its meshes as well.
  const auto range = run_weft(render + " --frames 5-7 --out " + (m_dir / "range").string());
  ASSERT_EQ(range.exit_code, 0) << range.output;
  EXPECT_TRUE(weft::app::test::file_bytes(run / remeshed_output_name("frame", 6, "png")) ==
              weft::app::test::file_bytes(m_dir / "range" / remeshed_output_name("frame", 6, "png")));
  // Without its meshes the states are refused, naming what is missing.
  for (int k = 0; k <= 8; ++k) fs::remove(run / remeshed_output_name("cloth_mesh", k, "weft"));
  const auto missing = run_weft(render + " --frames 3 --out " + (m_dir / "none").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_CONTAINS(missing.output, "no cloth_mesh_NNNN.weft at or before frame");
}

}  // namespace
