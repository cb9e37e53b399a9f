// simulation.remesh in a scene file (docs/remeshing.md): a triangle-mesh cloth
// hung from its top edge is remeshed as it runs (its vertex count changes, its pins stay put);
// keys out of range and the combinations that cannot be remeshed are errors naming the key.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "scene_test_support.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
using test::rectangle_obj;

fs::path remesh_test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) / "weft_remesh_scene_test" / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A 40 × 40 cm triangle-mesh square (5 cm cells) written beside the scene, lying flat 1 m up
// and held along its far edge (v = 40 cm), remeshed every 10 steps of implicit Euler.
Json remeshed_hang(const fs::path& dir) {
  std::ofstream(dir / "square.obj") << rectangle_obj(9, 9, 0.4, 0.4, 1.0, true);
  return Json::parse(R"({
    "description": "a remeshed hanging square",
    "cloth": {"mesh": "square.obj",
              "material": {"density": "0.2 kg/m^2", "stretch_warp": "200 N/m",
                           "stretch_weft": "150 N/m", "shear": "20 N/m",
                           "bend_warp": "2e-4 N*m", "bend_weft": "1e-4 N*m"},
              "pins": [{"region": {"u": [0, 1], "v": [1, 1]}}]},
    "simulation": {"model": "baraff_witkin", "integrator": "implicit_euler",
                   "remesh": {"every": 10, "c": "1 mm", "h_min": "1 cm", "h_max": "5 cm"}},
    "output": {"fps": 24, "frames": 4}
  })");
}

std::string simulator_error(const Json& scene, const fs::path& dir) {
  try {
    make_simulator(parse_scene(scene.dump(), (dir / "scene.json").string()));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RemeshScene, AHangingTriangleMeshIsRemeshedAndKeepsItsPins) {
  const fs::path dir = remesh_test_dir();
  const Scene scene = parse_scene(remeshed_hang(dir).dump(), (dir / "scene.json").string());
  EXPECT_TRUE(scene.sim.remesh.enabled);
  EXPECT_EQ(scene.sim.remesh.every_steps, 10);
  EXPECT_DOUBLE_EQ(scene.sim.remesh.h_min_m, 0.01);
  const auto simulator = make_simulator(scene);
  const sim::Index before = simulator->mesh().vertex_count();
  const std::size_t pinned = simulator->pinned().size();
  ASSERT_EQ(pinned, 9u);
  sim::Matrix3X pins(9, 3);
  for (std::size_t k = 0; k < pinned; ++k)
    pins.row(static_cast<Eigen::Index>(k)) = simulator->state().x.row(simulator->pinned()[k]);
  simulator->advance(4.0 / 24.0);  // 20 steps of 1/120 s: two remeshes
  EXPECT_EQ(simulator->remesh_count(), 2);
  EXPECT_NE(simulator->mesh().vertex_count(), before);
  EXPECT_TRUE(simulator->state().x.allFinite());
  ASSERT_EQ(simulator->pinned().size(), pinned);
  for (std::size_t k = 0; k < pinned; ++k)  // bit for bit
    EXPECT_EQ(simulator->state().x.row(simulator->pinned()[k]), pins.row(static_cast<Eigen::Index>(k)));
  EXPECT_LT(simulator->state().x.col(2).minCoeff(), 0.95) << "it swings down";
}

TEST(RemeshScene, KeysOutOfRangeAreErrorsNamingThem) {
  const fs::path dir = remesh_test_dir();
  Json scene = remeshed_hang(dir);
  scene["simulation"]["remesh"]["h_max"] = "5 mm";
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"),
                  "simulation.remesh.h_max: expected at least h_min");
  scene = remeshed_hang(dir);
  scene["simulation"]["remesh"]["every"] = 0;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"), "simulation.remesh.every");
  scene = remeshed_hang(dir);
  EXPECT_EQ(parse_scene(scene.dump(), (dir / "scene.json").string()).sim.remesh.relax_steps, 4);
  scene["simulation"]["remesh"]["relax"] = 0;
  EXPECT_EQ(parse_scene(scene.dump(), (dir / "scene.json").string()).sim.remesh.relax_steps, 0);
  scene["simulation"]["remesh"]["relax"] = -1;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"), "simulation.remesh.relax");
  scene["simulation"]["remesh"]["relax"] = 2.5;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"), "simulation.remesh.relax");
  scene = remeshed_hang(dir);
  scene["simulation"]["remesh"]["h_mni"] = "1 cm";
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"), "h_mni");
}

TEST(RemeshScene, TheIndicatorAndTheTransferAreRead) {
  const fs::path dir = remesh_test_dir();
  Json json = remeshed_hang(dir);
  EXPECT_EQ(parse_scene(json.dump(), (dir / "scene.json").string()).sim.remesh.indicator, 0.0);
  EXPECT_EQ(parse_scene(json.dump(), (dir / "scene.json").string()).sim.remesh.transfer,
            sim::remesh::PositionTransfer::quadratic);
  json["simulation"]["remesh"]["indicator"] = 2.5;
  json["simulation"]["remesh"]["transfer"] = "linear";
  const Scene scene = parse_scene(json.dump(), (dir / "scene.json").string());
  EXPECT_EQ(scene.sim.remesh.indicator, 2.5);
  EXPECT_EQ(scene.sim.remesh.transfer, sim::remesh::PositionTransfer::linear);
  // Remeshed only when max |κ|h² passes 2.5 c: the square swings down and curves.
  const auto simulator = make_simulator(scene);
  simulator->advance(4.0 / 24.0);
  EXPECT_GE(simulator->remesh_count(), 1);
  EXPECT_LE(simulator->remesh_count(), 2);
}

TEST(RemeshScene, BadIndicatorsAndTransfersAreErrorsNamingTheKey) {
  const fs::path dir = remesh_test_dir();
  Json scene = remeshed_hang(dir);
  scene["simulation"]["remesh"]["indicator"] = 1.0;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"),
                  "simulation.remesh.indicator: expected a multiple of c above 1");
  scene["simulation"]["remesh"]["indicator"] = -3;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"), "simulation.remesh.indicator");
  scene["simulation"]["remesh"]["indicator"] = "2 mm";
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"), "simulation.remesh.indicator");
  // coarsen: a ratio above 1, and only with the indicator.
  scene = remeshed_hang(dir);
  scene["simulation"]["remesh"]["coarsen"] = 2;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"),
                  "simulation.remesh.coarsen: needs \"indicator\"");
  scene["simulation"]["remesh"]["indicator"] = 3;
  scene["simulation"]["remesh"]["coarsen"] = 1;
  EXPECT_CONTAINS(test::scene_error_of(scene, dir / "scene.json"),
                  "simulation.remesh.coarsen: expected a ratio above 1");
  scene["simulation"]["remesh"]["coarsen"] = 2.5;
  EXPECT_EQ(parse_scene(scene.dump(), (dir / "scene.json").string()).sim.remesh.coarsen, 2.5);
  scene = remeshed_hang(dir);
  scene["simulation"]["remesh"]["transfer"] = "cubic";
  const std::string transfer = test::scene_error_of(scene, dir / "scene.json");
  EXPECT_CONTAINS(transfer, "simulation.remesh.transfer");
  EXPECT_CONTAINS(transfer, "quadratic");
}

TEST(RemeshScene, WhatCannotBeRemeshedIsAInputErrorNamingTheReason) {
  const fs::path dir = remesh_test_dir();
  Json springs = remeshed_hang(dir);
  springs["simulation"]["model"] = "mass_spring";
  const std::string model = simulator_error(springs, dir);
  EXPECT_CONTAINS(model, "scene.json: simulation.remesh: not with simulation.model \"mass_spring\"");
  EXPECT_CONTAINS(model, "use baraff_witkin");
  Json rft = remeshed_hang(dir);
  rft["simulation"]["model"] = "rft3";
  EXPECT_CONTAINS(simulator_error(rft, dir), "simulation.remesh: not with simulation.model \"rft3\"");

  Json grid = remeshed_hang(dir);
  grid["cloth"].erase("mesh");
  grid["cloth"]["size"] = {"40 cm", "40 cm"};
  grid["cloth"]["resolution"] = {9, 9};
  EXPECT_CONTAINS(simulator_error(grid, dir),
                  "simulation.remesh: needs a triangle-mesh cloth (cloth.mesh, a file of triangles)");

  Json projected = remeshed_hang(dir);
  projected["simulation"]["constraints"] = {{"method", "fast_projection"}};
  EXPECT_CONTAINS(simulator_error(projected, dir), "warp/weft");

  Json explicit_step = remeshed_hang(dir);
  explicit_step["simulation"]["integrator"] = "symplectic_euler";
  EXPECT_CONTAINS(simulator_error(explicit_step, dir),
                  "simulation.remesh: needs simulation.integrator implicit_euler or "
                  "dynamic_relaxation");
}

}  // namespace
}  // namespace weft::app
