// Material presets: the lookup, its error, Kang & Yu's wool as sim::Material's default, each
// preset's numbers against the published figures in their own units, and every preset usable by
// the mass-spring model.
#include "sim/material_presets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// Luible (2008), Annex G, typed from the transcription cited in sim/material_presets.cpp, in its
// units: weight g/m², tensile rigidity warp and weft N/m, shear rigidity N/m (per unit shear
// strain). The presets must give these back after their conversion to SI.
struct AnnexGFabric {
  const char* preset;
  const char* fabric;  // Luible's fabric number, as the source string must name it
  double weight_g_m2, tensile_warp_N_m, tensile_weft_N_m, shear_N_m;
};
constexpr AnnexGFabric annex_g[] = {
    {"cotton_shirting", "fabric 02", 120.0, 2000.0, 3000.0, 20.0},
    {"silk_mulberry", "fabric 07", 15.0, 6000.0, 4500.0, 10.0},
    {"denim", "fabric 01", 380.0, 1800.0, 3000.0, 102.0},
};

TEST(MaterialPresets, LuibleFabricsGiveBackAnnexGInItsUnits) {
  for (const AnnexGFabric& f : annex_g) {
    SCOPED_TRACE(f.preset);
    const MaterialPreset& p = material_preset(f.preset);
    EXPECT_NEAR(p.material.density_kg_m2 * 1e3, f.weight_g_m2, 1e-9 * f.weight_g_m2);
    EXPECT_NEAR(p.material.stretch_warp_N_m, f.tensile_warp_N_m, 1e-9 * f.tensile_warp_N_m);
    EXPECT_NEAR(p.material.stretch_weft_N_m, f.tensile_weft_N_m, 1e-9 * f.tensile_weft_N_m);
    EXPECT_NEAR(p.material.shear_N_m, f.shear_N_m, 1e-9 * f.shear_N_m);
    EXPECT_NE(p.source.find("Luible 2008"), std::string::npos) << p.source;
    EXPECT_NE(p.source.find("Annex G"), std::string::npos) << p.source;
    EXPECT_NE(p.source.find(f.fabric), std::string::npos) << p.source;
  }
}

// The textile units against values worked by hand: 1 gf = 1e-3 kg × 9.80665 m/s² = 9.80665e-3 N,
// so 1 gf/cm = 0.980665 N/m, 1 gf·cm (gf·cm²/cm) = 9.80665e-5 N·m, and 1 gf/cm² is the weight of
// 1 g/cm² = 10 kg/m². KES's shear rigidity G is per degree of shear angle: 1 gf/(cm·deg) per
// radian is 180/π = 57.296 gf/cm = 56.188 N/m (Luible's Annex F writes G(tan θ) = 57.3 G(θ°)).
TEST(MaterialPresets, TextileUnitsConvertAsWorkedByHand) {
  EXPECT_NEAR(textile::gf_per_cm(1.0), 0.980665, 1e-12);
  EXPECT_NEAR(textile::gf_cm(1.0), 9.80665e-5, 1e-17);
  EXPECT_NEAR(textile::gf_per_cm2(1.0), 10.0, 1e-12);
  EXPECT_NEAR(textile::gf_per_cm(180.0 / M_PI), 56.188, 1e-3);
  // Kang & Yu's wool by hand: 0.019 gf/cm² = 0.19 kg/m² (190 g/m²); 41.8 gf/cm = 40.992 N/m.
  EXPECT_NEAR(textile::gf_per_cm2(0.019) * 1e3, 190.0, 1e-9);
  EXPECT_NEAR(textile::gf_per_cm(41.8), 40.9918, 1e-4);
}

// Peirce's cantilever bending length c = (B/W)^{1/3}, in cm for B in gf·cm and W in gf/cm², with
// standard gravity g0 = 9.80665 m/s² (1 gf·cm = 9.80665e-5 N·m; 1 gf/cm² weighs 1 g/cm² = 10 kg/m²).
double bending_length_cm(double bend_Nm, double density_kg_m2) {
  return 100.0 * peirce_bending_length_m(bend_Nm, density_kg_m2, 9.80665);
}

// In textile units by hand: Kang & Yu's wool, B = 0.083 / 0.063 gf·cm over W = 0.019 gf/cm²,
// c = (0.083/0.019)^(1/3) = 1.6347 cm and (0.063/0.019)^(1/3) = 1.4912 cm. The SI function must
// give the same from the SI values; under a weaker gravity a strip bends less (c ∝ g^(-1/3)).
TEST(MaterialPresets, PeirceBendingLengthMatchesTheHandValue) {
  const Material& wool = material_preset("wool_kang_yu").material;
  EXPECT_NEAR(bending_length_cm(wool.bend_warp_Nm, wool.density_kg_m2), 1.6347, 1e-4);
  EXPECT_NEAR(bending_length_cm(wool.bend_weft_Nm, wool.density_kg_m2), 1.4912, 1e-4);
  EXPECT_NEAR(peirce_bending_length_m(wool.bend_warp_Nm, wool.density_kg_m2, 9.80665 / 8.0),
              2.0 * 1.6347e-2, 2e-6);
  EXPECT_EQ(peirce_bending_length_m(0.0, 0.19, 9.81), 0.0);
  EXPECT_THROW((void)peirce_bending_length_m(-1e-6, 0.19, 9.81), std::invalid_argument);
  EXPECT_THROW((void)peirce_bending_length_m(1e-6, 0.0, 9.81), std::invalid_argument);
  EXPECT_THROW((void)peirce_bending_length_m(1e-6, 0.19, 0.0), std::invalid_argument);
  EXPECT_THROW((void)peirce_bending_length_m(NAN, 0.19, 9.81), std::invalid_argument);
}

// Provenance: a preset is fully published exactly when no field is representative, a published
// drape coefficient lies in [0, 1], and a source that gives none says so.
TEST(MaterialPresets, ProvenanceIsStatedPerPreset) {
  for (const MaterialPreset& p : material_presets()) {
    SCOPED_TRACE(p.name);
    EXPECT_EQ(p.fully_published(), p.representative_fields.empty());
    if (p.drape_coefficient) {
      EXPECT_GE(*p.drape_coefficient, 0.0);
      EXPECT_LE(*p.drape_coefficient, 1.0);
    } else {
      EXPECT_NE(p.source.find("no drape coefficient"), std::string::npos) << p.source;
    }
  }
  EXPECT_TRUE(material_preset("wool_kang_yu").fully_published());
  EXPECT_FALSE(material_preset("denim").fully_published());
}

// The Luible presets' bending rigidities are no measurement (none was found): each preset says so,
// and they are B = W c³ for the stated representative bending lengths.
TEST(MaterialPresets, RepresentativeBendingIsFlaggedAndHasTheStatedBendingLength) {
  struct Lengths {
    const char* preset;
    double warp_cm, weft_cm;
  };
  for (const Lengths& l : {Lengths{"cotton_shirting", 1.8, 1.6}, Lengths{"silk_mulberry", 1.25, 1.2},
                           Lengths{"denim", 3.35, 2.8}}) {
    SCOPED_TRACE(l.preset);
    const MaterialPreset& p = material_preset(l.preset);
    EXPECT_EQ(p.representative_fields, "bend_warp, bend_weft");
    EXPECT_NE(p.source.find("representative"), std::string::npos) << p.source;
    EXPECT_NEAR(bending_length_cm(p.material.bend_warp_Nm, p.material.density_kg_m2), l.warp_cm,
                1e-9);
    EXPECT_NEAR(bending_length_cm(p.material.bend_weft_Nm, p.material.density_kg_m2), l.weft_cm,
                1e-9);
  }
  // Kang & Yu's wool is measured throughout; its bending length is the one cantilever_test uses.
  const MaterialPreset& wool = material_preset("wool_kang_yu");
  EXPECT_TRUE(wool.representative_fields.empty());
  EXPECT_NEAR(bending_length_cm(wool.material.bend_warp_Nm, wool.material.density_kg_m2), 1.635,
              1e-3);
}

// Physical sanity of the data: the light silk is lighter and shears more easily than the
// shirting, which is lighter and shears more easily than the denim (Annex G); the representative
// bending rigidities keep the same order. Woven cloth resists stretch far more than shear.
TEST(MaterialPresets, SilkCottonDenimAreOrderedByWeightShearAndBending) {
  const Material& silk = material_preset("silk_mulberry").material;
  const Material& cotton = material_preset("cotton_shirting").material;
  const Material& denim = material_preset("denim").material;
  EXPECT_LT(silk.density_kg_m2, cotton.density_kg_m2);
  EXPECT_LT(cotton.density_kg_m2, denim.density_kg_m2);
  EXPECT_LT(silk.shear_N_m, cotton.shear_N_m);
  EXPECT_LT(cotton.shear_N_m, denim.shear_N_m);
  for (auto bend : {&Material::bend_warp_Nm, &Material::bend_weft_Nm}) {
    EXPECT_LT(silk.*bend, cotton.*bend);
    EXPECT_LT(cotton.*bend, denim.*bend);
  }
  for (const MaterialPreset& p : material_presets()) {
    const Material& m = p.material;
    EXPECT_GT(std::min(m.stretch_warp_N_m, m.stretch_weft_N_m), 10.0 * m.shear_N_m) << p.name;
  }
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
