// The cloth model in scene files ("simulation.model") and zero rigidities: the choice lands in
// sim::SimSettings, mistakes name their key, and the simulator builds only the terms the scene
// needs (what `weft run --explain` lists).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "sim/pins.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json model_scene(const std::string& model) {
  Json j = Json::parse(R"({
    "description": "test scene for the cloth model",
    "cloth": {"size": ["40 cm", "40 cm"], "resolution": [9, 9],
              "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
    "simulation": {}
  })");
  j["simulation"]["model"] = model;
  return j;
}

std::string forces_line(const Scene& scene) {
  const sim::ClothMesh mesh = sim::make_grid(scene.grid);
  const sim::Simulator simulator(mesh, scene.material, sim::resolve_pins(scene.pins, mesh),
                                 scene.sim);
  for (const std::string& line : simulator.explain())
    if (line.rfind("forces", 0) == 0) return line;
  return "no forces line";
}

TEST(ModelScene, EachModelParses) {
  EXPECT_EQ(test::parse_json_scene(model_scene("mass_spring")).sim.model,
            sim::ClothModel::mass_spring);
  for (sim::ClothModel m : sim::all_cloth_models)
    EXPECT_EQ(test::parse_json_scene(model_scene(sim::cloth_model_name(m))).sim.model, m);
  Json omitted = model_scene("mass_spring");
  omitted["simulation"].erase("model");
  EXPECT_EQ(test::parse_json_scene(omitted).sim.model, sim::ClothModel::mass_spring);
}

TEST(ModelScene, AnUnknownModelListsTheChoices) {
  EXPECT_EQ(test::scene_error_of(model_scene("fem")),
            "scene.json: simulation.model: expected one of 'mass_spring', 'baraff_witkin', "
            "'rft3', 'rft6', got the string 'fem'");
}

TEST(ModelScene, ZeroRigiditiesAreAllowedNegativeOnesAreNot) {
  Json j = model_scene("baraff_witkin");
  j["cloth"]["material"] = {{"shear", 0}, {"bend_warp", 0}, {"bend_weft", 0}};
  EXPECT_NO_THROW(test::parse_json_scene(j));
  j["cloth"]["material"]["bend_weft"] = "-0.01 gf*cm";
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: cloth.material.bend_weft:");
}

TEST(ModelScene, OnlyTheNeededTermsAreBuilt) {
  for (const char* model : {"mass_spring", "baraff_witkin", "rft3", "rft6"}) {
    SCOPED_TRACE(model);
    Json j = model_scene(model);
    const auto has_shear = [](const std::string& line) {
      return line.find("shear") != std::string::npos || line.find("membrane") != std::string::npos;
    };
    const std::string all = forces_line(test::parse_json_scene(j));
    EXPECT_CONTAINS(all, "bending");
    EXPECT_TRUE(has_shear(all)) << all;
    j["cloth"]["material"] = {{"bend_warp", 0}, {"bend_weft", 0}};
    const std::string no_bending = forces_line(test::parse_json_scene(j));
    EXPECT_EQ(no_bending.find("bending"), std::string::npos) << no_bending;
    EXPECT_TRUE(has_shear(no_bending)) << no_bending;
  }
  // Inextensible warp and weft: the continuum keeps shear and bending, drops stretch.
  Json j = model_scene("baraff_witkin");
  j["simulation"]["integrator"] = "implicit_euler";
  j["simulation"]["constraints"] = {{"method", "fast_projection"}};
  const std::string constrained = forces_line(test::parse_json_scene(j));
  EXPECT_EQ(constrained.find("stretch"), std::string::npos) << constrained;
  EXPECT_CONTAINS(constrained, "Baraff–Witkin shear");
}

// make_simulator labels material errors, and only those, with the material's key: another
// setting the simulator refuses is still bad input, but not called a material error.
std::string make_simulator_error(const Scene& scene) {
  try {
    make_simulator(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MakeSimulator, OnlyMaterialErrorsAreCalledMaterialErrors) {
  Json j = model_scene("mass_spring");
  j["simulation"]["constraints"] = {{"method", "none"}};  // stretch springs: shear must be below
  j["cloth"]["material"] = {{"shear", "5000 N/m"}};
  const std::string material = make_simulator_error(test::parse_json_scene(j));
  EXPECT_CONTAINS(material, "scene.json: cloth.material: shear rigidity");

  Scene scene = test::parse_json_scene(model_scene("mass_spring"));
  scene.sim.self_collision.enabled = true;
  scene.sim.self_collision.threads = -1;  // not a material error
  const std::string other = make_simulator_error(scene);
  EXPECT_CONTAINS(other, "scene.json: ");
  EXPECT_CONTAINS(other, "self_collision.threads");
  EXPECT_EQ(other.find("material"), std::string::npos) << other;
}


// The continuum models run under every integrator kind: explicit at their automatic step,
// implicit, and with fast projection; the sheet hangs below its pins and stays finite.
class ContinuumModelScene : public ::testing::TestWithParam<const char*> {};

TEST_P(ContinuumModelScene, DrivesTheSimulator) {
  const std::vector<std::pair<std::string, Json>> variants{
      {"symplectic", Json::object()},
      {"implicit", {{"integrator", "implicit_euler"}}},
      {"projected",
       {{"integrator", "implicit_euler"}, {"constraints", {{"method", "fast_projection"}}}}}};
  for (const auto& [name, simulation] : variants) {
    SCOPED_TRACE(name);
    Json j = model_scene(GetParam());
    j["simulation"].update(simulation);
    const Scene scene = test::parse_json_scene(j);
    const sim::ClothMesh mesh = sim::make_grid(scene.grid);
    sim::Simulator simulator(mesh, scene.material, sim::resolve_pins(scene.pins, mesh), scene.sim);
    ASSERT_NO_THROW(simulator.advance(0.25));
    const sim::Diagnostics d = simulator.diagnostics();
    EXPECT_GT(d.elastic_energy_J, 0.0);
    EXPECT_LT(d.max_strain, 0.05);
    // The free corners have fallen.
    EXPECT_LT(simulator.state().x(mesh.index(0, 0), 2), scene.grid.origin.z() - 0.05);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, ContinuumModelScene,
                         ::testing::Values("baraff_witkin", "rft3", "rft6"));

}  // namespace
}  // namespace weft::app
