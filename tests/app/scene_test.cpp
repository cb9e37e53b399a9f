// Valid scene files: every key lands in the right field, in SI units.

#include "app/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/constants.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

using test::expect_close;
using test::gram_force;

// Every key of the format, most in textile or non-SI units.
const char* const complete_scene = R"({
  "description": "Every key: a test scene for the parser.",
  "cloth": {
    "size": ["50 cm", 0.25],
    "resolution": [21, 11],
    "origin": ["-25 cm", 0, "1200 mm"],
    "warp_axis": [0, 1, 0],
    "weft_axis": [0, 0, -1.0000000001],
    "material": {
      "density": "190 g/m^2",
      "stretch_warp": "1118.2 gf/cm",
      "stretch_weft": 744.8,
      "shear": "41.8 gf/cm",
      "bend_warp": "0.083 gf*cm",
      "bend_weft": "6.2 uN*m"
    },
    "pins": [
      {"corner": "u0v1"},
      {"vertex": 17},
      {"grid": [3, 4]},
      {"region": {"u": [0, 1], "v": [0.95, 1]}}
    ]
  },
  "simulation": {
    "model": "mass_spring",
    "integrator": "symplectic_euler",
    "gravity": [0, "-981 cm/s^2", 0],
    "air_damping": "2 1/s",
    "time_step": "0.2 ms",
    "time_step_safety": 0.25,
    "max_speed": "360 km/h"
  },
  "output": {"fps": 30, "frames": 90},
  "render": {
    "size": [320, 240],
    "camera": {"eye": [1, 2, 3], "target": ["10 cm", 0, 0], "up": [0, 0, 1], "fov": "0.5 rad",
               "near": "5 mm", "far": 50},
    "light": {"direction": [0, 0, 2], "intensity": 1.5, "ambient": 0.1},
    "colors": {"front": [1, 0, 0], "back": [0, 1, 0], "background": [0, 0, 1]},
    "ground": {"z": "-1 cm", "half_size": "2 m", "color": [0.5, 0.5, 0.5]},
    "shading": "normals",
    "msaa": 8
  }
})";

TEST(Scene, CompleteSceneLandsInSIUnits) {
  const Scene s = parse_scene(complete_scene, "scenes/complete.json");
  EXPECT_EQ(s.source, "scenes/complete.json");
  EXPECT_EQ(s.name, "complete");
  EXPECT_EQ(s.text, complete_scene);
  EXPECT_EQ(s.description, "Every key: a test scene for the parser.");

  expect_close(s.grid.size_u_m, 0.5);
  expect_close(s.grid.size_v_m, 0.25);
  EXPECT_EQ(s.grid.nu, 21);
  EXPECT_EQ(s.grid.nv, 11);
  expect_close(s.grid.origin.x(), -0.25);
  EXPECT_EQ(s.grid.origin.y(), 0.0);
  expect_close(s.grid.origin.z(), 1.2);
  EXPECT_EQ(s.grid.warp_axis, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(s.grid.weft_axis, Eigen::Vector3d(0, 0, -1));  // normalised: within 1e-6 of unit

  expect_close(s.material.density_kg_m2, 0.19);
  expect_close(s.material.stretch_warp_N_m, 1118.2 * gram_force / 0.01);
  expect_close(s.material.stretch_weft_N_m, 744.8);
  expect_close(s.material.shear_N_m, 41.8 * gram_force / 0.01);
  expect_close(s.material.bend_warp_Nm, 0.083 * gram_force * 0.01);
  expect_close(s.material.bend_weft_Nm, 6.2e-6);

  ASSERT_EQ(s.pins.size(), 4u);
  EXPECT_EQ(std::get<sim::PinCorner>(s.pins[0]).name, "u0v1");
  EXPECT_EQ(std::get<sim::PinVertex>(s.pins[1]).index, 17);
  EXPECT_EQ(std::get<sim::PinGrid>(s.pins[2]).i, 3);
  EXPECT_EQ(std::get<sim::PinGrid>(s.pins[2]).j, 4);
  const auto region = std::get<sim::PinRegion>(s.pins[3]);
  EXPECT_EQ(region.u0, 0.0);
  EXPECT_EQ(region.u1, 1.0);
  EXPECT_EQ(region.v0, 0.95);
  EXPECT_EQ(region.v1, 1.0);

  EXPECT_EQ(s.sim.integrator, sim::Integrator::symplectic_euler);
  EXPECT_EQ(s.sim.gravity_m_s2.x(), 0.0);
  expect_close(s.sim.gravity_m_s2.y(), -9.81);
  expect_close(s.sim.air_damping_1_s, 2.0);
  ASSERT_EQ(s.sim.time_step.kind, sim::TimeStep::Kind::fixed);
  expect_close(s.sim.time_step.fixed_s, 2e-4);
  EXPECT_EQ(s.sim.time_step_safety, 0.25);
  expect_close(s.sim.max_speed_m_s, 100.0);

  EXPECT_EQ(s.fps, 30.0);
  EXPECT_EQ(s.frames, 90);

  const render::RenderSettings& r = s.render;
  EXPECT_EQ(r.width, 320);
  EXPECT_EQ(r.height, 240);
  EXPECT_EQ(r.camera.eye, Eigen::Vector3d(1, 2, 3));
  expect_close(r.camera.target.x(), 0.1);
  expect_close(r.camera.fov_y_deg, 0.5 * 180.0 / base::kPi);
  expect_close(r.camera.near_m, 0.005);
  EXPECT_EQ(r.camera.far_m, 50.0);
  EXPECT_EQ(r.light_direction, Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(r.light_intensity, 1.5);
  EXPECT_EQ(r.ambient, 0.1);
  EXPECT_EQ(r.front_color, Eigen::Vector3f(1, 0, 0));
  ASSERT_TRUE(r.back_color.has_value());
  EXPECT_EQ(*r.back_color, Eigen::Vector3f(0, 1, 0));
  EXPECT_EQ(r.background, Eigen::Vector3f(0, 0, 1));
  EXPECT_TRUE(r.ground);
  expect_close(r.ground_z_m, -0.01);
  EXPECT_EQ(r.ground_half_size_m, 2.0);
  EXPECT_EQ(r.ground_color, Eigen::Vector3f(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(r.shading, render::Shading::normals);
  EXPECT_EQ(r.msaa_samples, 8);
}

TEST(Scene, PinsResolveOnTheGrid) {
  const Scene s = parse_scene(complete_scene, "complete.json");
  const auto pinned = sim::resolve_pins(s.pins, sim::make_grid(s.grid));
  // u0v1 = (0, 10) → 210; vertex 17; grid (3, 4) → 87; region v ≥ 0.95 → the row j = 10.
  std::vector<sim::Index> expected{17, 87};
  for (sim::Index i = 0; i < 21; ++i) expected.push_back(210 + i);
  EXPECT_EQ(pinned, expected);
}

TEST(Scene, OmittedBlocksAndKeysTakeTheStructDefaults) {
  const Scene s =
      parse_scene(R"({"description": "minimal", "cloth": {"size": [2, 3], "resolution": [4, 5]}})",
                  "minimal.json");
  const sim::GridSpec grid;
  const sim::Material material;
  const sim::SimSettings settings;
  const render::RenderSettings render;
  EXPECT_EQ(s.grid.origin, grid.origin);
  EXPECT_EQ(s.grid.warp_axis, grid.warp_axis);
  EXPECT_EQ(s.grid.weft_axis, grid.weft_axis);
  EXPECT_EQ(s.material.density_kg_m2, material.density_kg_m2);
  EXPECT_EQ(s.material.bend_weft_Nm, material.bend_weft_Nm);
  EXPECT_TRUE(s.pins.empty());  // no pins: free fall
  EXPECT_EQ(s.sim.gravity_m_s2, settings.gravity_m_s2);
  EXPECT_EQ(s.sim.air_damping_1_s, settings.air_damping_1_s);
  EXPECT_EQ(s.sim.time_step.kind, sim::TimeStep::Kind::automatic);
  EXPECT_EQ(s.sim.time_step_safety, settings.time_step_safety);
  EXPECT_EQ(s.fps, 24.0);
  EXPECT_EQ(s.frames, 72);
  EXPECT_EQ(s.render.width, render.width);
  EXPECT_EQ(s.render.camera.eye, render.camera.eye);
  EXPECT_EQ(s.render.camera.fov_y_deg, render.camera.fov_y_deg);
  EXPECT_EQ(s.render.ground, render.ground);
  EXPECT_EQ(s.render.shading, render.shading);
  EXPECT_EQ(s.render.msaa_samples, render.msaa_samples);
}

TEST(Scene, AlternativeForms) {
  const Scene s = parse_scene(R"({
    "description": "alternative forms",
    "cloth": {"size": [1, 1], "resolution": [3, 3]},
    "simulation": {"time_step": "auto", "gravity": ["0 m/s^2", 0, -9.81]},
    "render": {"ground": false, "camera": {"fov": 55}}
  })",
                              "alt.json");
  EXPECT_EQ(s.sim.time_step.kind, sim::TimeStep::Kind::automatic);
  EXPECT_EQ(s.sim.gravity_m_s2, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_FALSE(s.render.ground);
  EXPECT_EQ(s.render.camera.fov_y_deg, 55.0);  // a bare number is in degrees
  const Scene t = parse_scene(
      R"({"description": "d", "cloth": {"size": [1, 1], "resolution": [3.0, 3]},
          "simulation": {"time_step": 0.001}, "render": {"ground": true}})",
      "alt2.json");
  EXPECT_EQ(t.grid.nu, 3);
  EXPECT_EQ(t.sim.time_step.kind, sim::TimeStep::Kind::fixed);
  EXPECT_EQ(t.sim.time_step.fixed_s, 0.001);
  EXPECT_TRUE(t.render.ground);
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Scene, DefaultSceneIsTheCompiledInAsset) {
  const std::filesystem::path asset =
      std::filesystem::path(WEFT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  EXPECT_EQ(default_scene_text(), read_file(asset));
  EXPECT_EQ(load_scene(asset).grid.nu, default_scene().grid.nu);
}

TEST(Scene, DefaultSceneIsTheTwoCornerHang) {
  const Scene s = default_scene();
  EXPECT_EQ(s.name, "default");
  EXPECT_EQ(s.source, "<built-in default scene>");
  EXPECT_NE(s.description.find("4.6"), std::string::npos);
  EXPECT_EQ(s.grid.nu, 41);
  EXPECT_EQ(s.grid.nv, 41);
  EXPECT_EQ(s.grid.size_u_m, 1.0);
  EXPECT_EQ(s.grid.size_v_m, 1.0);
  EXPECT_EQ(s.grid.origin, Eigen::Vector3d(-0.5, 0, 1.6));
  // Kang & Yu wool; sim::Material's defaults are the same fabric, rounded.
  const sim::Material rounded;
  EXPECT_NEAR(s.material.density_kg_m2, rounded.density_kg_m2, 0.01 * rounded.density_kg_m2);
  EXPECT_NEAR(s.material.stretch_warp_N_m, rounded.stretch_warp_N_m,
              0.01 * rounded.stretch_warp_N_m);
  EXPECT_NEAR(s.material.stretch_weft_N_m, rounded.stretch_weft_N_m,
              0.01 * rounded.stretch_weft_N_m);
  EXPECT_NEAR(s.material.shear_N_m, rounded.shear_N_m, 0.01 * rounded.shear_N_m);
  EXPECT_NEAR(s.material.bend_warp_Nm, rounded.bend_warp_Nm, 0.01 * rounded.bend_warp_Nm);
  EXPECT_NEAR(s.material.bend_weft_Nm, rounded.bend_weft_Nm, 0.01 * rounded.bend_weft_Nm);
  // Pinned at the two adjacent corners of the back edge (v = 1), nothing else.
  const auto pinned = sim::resolve_pins(s.pins, sim::make_grid(s.grid));
  EXPECT_EQ(pinned, (std::vector<sim::Index>{40 * 41, 40 * 41 + 40}));
  EXPECT_EQ(s.sim.air_damping_1_s, 5.0);  // seed 002 §4.6: α = 5 s⁻¹
  EXPECT_EQ(s.sim.gravity_m_s2, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_EQ(s.fps, 24.0);
  EXPECT_EQ(s.frames, 72);
  EXPECT_TRUE(s.render.ground);
  EXPECT_EQ(s.render.ground_z_m, 0.0);
}

TEST(Scene, TheExampleInTheDocsParses) {
  const std::string doc = read_file(std::filesystem::path(WEFT_SOURCE_DIR) / "docs" / "scene.md");
  const std::string open = "```json\n";
  const std::size_t begin = doc.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = doc.find("\n```", begin + open.size());
  ASSERT_NE(end, std::string::npos);
  const Scene s = parse_scene(doc.substr(begin + open.size(), end - begin - open.size() + 1),
                              "docs/scene.md");
  expect_close(s.grid.size_u_m, 0.2);
  EXPECT_EQ(s.grid.nu, 41);
  EXPECT_EQ(s.sim.air_damping_1_s, 5.0);
  EXPECT_EQ(s.pins.size(), 2u);
}

TEST(Scene, LoadSceneNamesTheSceneAfterTheFileStem) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "weft_scene_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "hang_test.json";
  const std::string text =
      R"({"description": "d", "cloth": {"size": ["1 m", "1 m"], "resolution": [5, 5]}})";
  std::ofstream(path) << text;
  const Scene s = load_scene(path);
  EXPECT_EQ(s.name, "hang_test");
  EXPECT_EQ(s.source, path.string());
  EXPECT_EQ(s.text, text);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace weft::app
