// "cloth.material.preset" in scene files: a preset sets every material value, each material key
// given besides it overrides that one value, and an unknown name lists the known ones.

#include <gtest/gtest.h>

#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "sim/material/material_presets.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json scene_with_material(const Json& material) {
  Json scene = Json::parse(R"({
    "description": "test scene with a material preset",
    "cloth": {"size": ["20 cm", "20 cm"], "resolution": [5, 5]}
  })");
  scene["cloth"]["material"] = material;
  return scene;
}

sim::Material material_of(const Json& material) {
  return parse_scene(scene_with_material(material).dump(2), "scene.json").material;
}

std::string material_error_of(const Json& material) {
  return test::scene_error_of(scene_with_material(material));
}

void expect_same(const sim::Material& a, const sim::Material& b) {
  EXPECT_EQ(a.density_kg_m2, b.density_kg_m2);
  EXPECT_EQ(a.stretch_warp_N_m, b.stretch_warp_N_m);
  EXPECT_EQ(a.stretch_weft_N_m, b.stretch_weft_N_m);
  EXPECT_EQ(a.shear_N_m, b.shear_N_m);
  EXPECT_EQ(a.bend_warp_Nm, b.bend_warp_Nm);
  EXPECT_EQ(a.bend_weft_Nm, b.bend_weft_Nm);
}

TEST(MaterialPresetScene, EveryPresetSetsEveryValue) {
  for (const sim::MaterialPreset& p : sim::material_presets()) {
    SCOPED_TRACE(p.name);
    expect_same(material_of({{"preset", p.name}}), p.material);
  }
}

TEST(MaterialPresetScene, WithoutAPresetTheDefaultIsKangYuWool) {
  expect_same(material_of(Json::object()), sim::material_preset("wool_kang_yu").material);
}

TEST(MaterialPresetScene, AGivenKeyOverridesThatValueOnly) {
  const sim::Material denim = sim::material_preset("wang2011_11oz_black_denim").material;
  const sim::Material m =
      material_of({{"preset", "wang2011_11oz_black_denim"}, {"bend_weft", "0.5 gf*cm"}});
  EXPECT_NEAR(m.bend_weft_Nm, 0.5 * 9.80665e-5, 1e-15);
  sim::Material expected = denim;
  expected.bend_weft_Nm = m.bend_weft_Nm;
  expect_same(m, expected);
  // Wherever the key stands in the object.
  const sim::Material light =
      material_of({{"density", "0.03 gf/cm^2"}, {"preset", "wang2011_gray_interlock"}});
  EXPECT_NEAR(light.density_kg_m2, 0.3, 1e-12);
  sim::Material interlock = sim::material_preset("wang2011_gray_interlock").material;
  interlock.density_kg_m2 = light.density_kg_m2;
  expect_same(light, interlock);
}

TEST(MaterialPresetScene, AnUnknownPresetListsTheKnownNames) {
  const std::string e = material_error_of({{"preset", "wool"}});
  EXPECT_CONTAINS(e, "scene.json: cloth.material.preset");
  EXPECT_CONTAINS(e, "'wool'");
  for (const std::string& name : sim::material_preset_names()) EXPECT_CONTAINS(e, "'" + name + "'");
}

TEST(MaterialPresetScene, APresetMustBeAString) {
  EXPECT_CONTAINS(material_error_of({{"preset", 3}}), "cloth.material.preset");
}

TEST(MaterialPresetScene, OverridesAreStillCheckedAndMisspeltKeysStillFail) {
  EXPECT_CONTAINS(material_error_of({{"preset", "wang2011_royal_target"}, {"shear", "-1 gf/cm"}}), "cloth.material.shear");
  EXPECT_CONTAINS(material_error_of({{"presets", "wang2011_royal_target"}}), "did you mean 'preset'");
}

}  // namespace
}  // namespace weft::app
