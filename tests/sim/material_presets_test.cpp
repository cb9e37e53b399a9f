// Material presets: the lookup, its error, Kang & Yu's wool as sim::Material's default, and every
// preset usable by the mass-spring model.
#include "sim/material_presets.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>

#include "sim/mass_spring.h"

namespace weft::sim {
namespace {

TEST(MaterialPresets, KangYuWoolIsTheDefaultMaterialInSIUnits) {
  const Material& wool = material_preset("wool_kang_yu").material;
  const Material defaults;
  EXPECT_EQ(wool.density_kg_m2, defaults.density_kg_m2);
  EXPECT_EQ(wool.stretch_warp_N_m, defaults.stretch_warp_N_m);
  EXPECT_EQ(wool.stretch_weft_N_m, defaults.stretch_weft_N_m);
  EXPECT_EQ(wool.shear_N_m, defaults.shear_N_m);
  EXPECT_EQ(wool.bend_warp_Nm, defaults.bend_warp_Nm);
  EXPECT_EQ(wool.bend_weft_Nm, defaults.bend_weft_Nm);
  // Seed 002's numbers: 0.019 gf/cm², 1118.2 / 759.5 gf/cm, 41.8 gf/cm, 0.083 / 0.063 gf·cm.
  EXPECT_NEAR(wool.density_kg_m2, 0.19, 1e-12);
  EXPECT_NEAR(wool.stretch_warp_N_m, 1096.58, 0.01);
  EXPECT_NEAR(wool.stretch_weft_N_m, 744.82, 0.01);
  EXPECT_NEAR(wool.shear_N_m, 40.99, 0.01);
  EXPECT_NEAR(wool.bend_warp_Nm, 8.1395e-6, 1e-10);
  EXPECT_NEAR(wool.bend_weft_Nm, 6.1782e-6, 1e-10);
}

TEST(MaterialPresets, NamesAreUniqueAndEachPresetStatesItsSource) {
  const auto names = material_preset_names();
  EXPECT_GE(names.size(), 4u);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
  for (const MaterialPreset& p : material_presets()) {
    EXPECT_FALSE(p.source.empty()) << p.name;
    EXPECT_EQ(&material_preset(p.name), &p);
  }
}

TEST(MaterialPresets, AnUnknownNameListsTheKnownOnes) {
  try {
    (void)material_preset("cotton");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown material preset 'cotton'"), std::string::npos) << what;
    for (const std::string& name : material_preset_names())
      EXPECT_NE(what.find(name), std::string::npos) << what;
  }
}

// Every preset builds the model on square cells (its shear rigidity is below its stretch
// rigidities) with positive stiffnesses.
TEST(MaterialPresets, EveryPresetBuildsTheMassSpringModel) {
  GridSpec spec;
  spec.nu = spec.nv = 5;
  const ClothMesh mesh = make_grid(spec);
  for (const MaterialPreset& p : material_presets()) {
    const Material& m = p.material;
    EXPECT_GT(m.density_kg_m2, 0.0) << p.name;
    EXPECT_LT(m.shear_N_m, m.stretch_weft_N_m) << p.name;
    const MassSpringModel model(mesh, m);
    for (const Spring& s : model.springs()) EXPECT_GT(s.k_N_m, 0.0) << p.name;
    for (const AngularSpring& b : model.bends()) EXPECT_GT(b.k_Nm, 0.0) << p.name;
  }
}

}  // namespace
}  // namespace weft::sim
