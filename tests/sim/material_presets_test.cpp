// Material presets: the lookup, its error, Kang & Yu's wool as sim::Material's default, the
// conversion of Wang et al.'s ARCSim material files (by hand, and against ARCSim's own energies),
// every preset's provenance and plausibility, and the models each preset builds.
#include "sim/material/material_presets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>

#include "sim/cloth_model.h"
#include "sim/continuum/hinge_bending.h"
#include "sim/mass_spring.h"
#include "tests/sim/cantilever_support.h"
#include "tests/sim/cylinder_bend.h"

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

TEST(MaterialPresets, NamesAreUniqueAndEachPresetStatesItsSource) {
  const auto names = material_preset_names();
  EXPECT_GE(names.size(), 9u);
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

// ARCSim's 11oz-black-denim (materials/11oz-black-denim.json), the file's values used.
ArcsimFabric arcsim_denim() {
  return {0.324, {205.352005, 10.234077, 1013.88629, 53.387184},
          {64.196457e-6, 73.384567e-6, 96.951576e-6}};
}

// The conversion by hand (sim/material/material_presets.cpp derives it from ARCSim's code): tensile
// rigidity = 2 × the strain-0 sample (dde.cpp doubles every sample; physics.cpp's energy is
// ½k ε²), shear = the c33 sample (k3 ε01² = ½(k3/2)γ² with k3 = 2·sample), bending = ke/4 (ARCSim's
// hinge ke·l²/(2(A0+A1))·θ²/4 is weft's ½·B·l²/(A0+A1)·θ²), warp from the edges along v (row 2).
// Denim: 2 × 205.352005 = 410.70401 N/m, 2 × 1013.88629 = 2027.77258 N/m, shear 53.387184 N/m,
// B = 96.951576e-6/4 = 24.237894e-6 N·m (warp), 64.196457e-6/4 = 16.049114e-6 N·m (weft); Peirce
// c = (B / (0.324 kg/m² × 9.80665 m/s²))^(1/3) = 1.9685 cm (warp), 1.7158 cm (weft).
TEST(MaterialPresets, ArcsimConversionMatchesTheHandComputedDenim) {
  const Material m = material_from_arcsim(arcsim_denim());
  EXPECT_EQ(m.density_kg_m2, 0.324);
  EXPECT_NEAR(m.stretch_warp_N_m, 410.70401, 1e-9);
  EXPECT_NEAR(m.stretch_weft_N_m, 2027.77258, 1e-9);
  EXPECT_NEAR(m.shear_N_m, 53.387184, 1e-12);
  EXPECT_NEAR(m.bend_warp_Nm, 24.237894e-6, 1e-15);
  EXPECT_NEAR(m.bend_weft_Nm, 16.04911425e-6, 1e-15);
  EXPECT_NEAR(bending_length_cm(m.bend_warp_Nm, m.density_kg_m2), 1.9685, 1e-4);
  EXPECT_NEAR(bending_length_cm(m.bend_weft_Nm, m.density_kg_m2), 1.7158, 1e-4);
  const Material& preset = material_preset("wang2011_11oz_black_denim").material;
  EXPECT_EQ(preset.bend_warp_Nm, m.bend_warp_Nm);
  EXPECT_EQ(preset.shear_N_m, m.shear_N_m);
  ArcsimFabric f = arcsim_denim();
  f.density_kg_m2 = 0.0;
  EXPECT_THROW((void)material_from_arcsim(f), std::invalid_argument);
  f = arcsim_denim();
  f.stretching[3] = -1.0;
  EXPECT_THROW((void)material_from_arcsim(f), std::invalid_argument);
  f = arcsim_denim();
  f.bending[2] = NAN;
  EXPECT_THROW((void)material_from_arcsim(f), std::invalid_argument);
}

// ARCSim's membrane energy per area (physics.cpp stretching_force, whose gradient it is) for a
// deformation gradient F = [x_u x_v] of the flat sheet, with k = 2 × the strain-0 sample
// (dde.cpp evaluate_stretching_sample, negatives clamped to 0).
double arcsim_membrane_energy_per_area(const ArcsimFabric& f, const Eigen::Matrix2d& F) {
  const Eigen::Matrix2d e = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  double k[4];
  for (int i = 0; i < 4; ++i) k[i] = 2.0 * std::max(f.stretching[i], 0.0);
  return 0.5 * k[0] * e(0, 0) * e(0, 0) + k[1] * e(0, 0) * e(1, 1) +
         0.5 * k[2] * e(1, 1) * e(1, 1) + k[3] * e(0, 1) * e(0, 1);
}

// The converted stretch and shear rigidities give ARCSim's energy for a small uniaxial strain
// (½ Y ε²) and a small simple shear (½ G γ², γ in radians; weft's models hold the same, e.g.
// BwMembrane.PureShearGivesTheContinuumEnergy). A factor 2 lost or gained would show as 50 %/100 %.
TEST(MaterialPresets, ArcsimMembraneEnergyIsTheConvertedStretchAndShear) {
  const ArcsimFabric f = arcsim_denim();
  const Material m = material_from_arcsim(f);
  const double eps = 1e-4, gamma = 1e-3;
  Eigen::Matrix2d F = Eigen::Matrix2d::Identity();
  F(0, 0) = 1.0 + eps;
  EXPECT_NEAR(arcsim_membrane_energy_per_area(f, F) / (0.5 * m.stretch_warp_N_m * eps * eps), 1.0,
              1e-3);
  F = Eigen::Matrix2d::Identity();
  F(1, 1) = 1.0 + eps;
  EXPECT_NEAR(arcsim_membrane_energy_per_area(f, F) / (0.5 * m.stretch_weft_N_m * eps * eps), 1.0,
              1e-3);
  F = Eigen::Matrix2d::Identity();
  F(0, 1) = gamma;  // simple shear: x_v = (γ, 1)
  // ε01 = γ/2 and ε11 = γ²/2: the shear term and a 4th-order stretch term of relative size γ².
  EXPECT_NEAR(arcsim_membrane_energy_per_area(f, F) / (0.5 * m.shear_N_m * gamma * gamma), 1.0,
              1e-3);
}

// ARCSim's bending energy (physics.cpp bending_force: ke·l²/(2(A0+A1))·θ²/4 per interior edge,
// ke by the edge's direction in material space, dde.cpp bending_stiffness: row 0 along u, 1 at
// 45°, 2 along v) on a sheet bent into a cylinder along warp or weft equals weft's HingeBending
// energy built from the converted rigidities — to rounding, since weft's hinges are the same
// discrete energy with B = ke/4 (both triangulations of each quad at half weight, as HingeBending
// does; an axis bend leaves the diagonals flat, so the 45° row does not enter). Swapping the rows
// would be off by 97/64 on this denim.
TEST(MaterialPresets, ArcsimHingeEnergyIsWeftsHingeEnergyOfTheConvertedRigidity) {
  const ArcsimFabric f = arcsim_denim();
  const Material m = material_from_arcsim(f);
  const double L = 0.1, kappa = 20.0;
  const Index n = 11;
  GridSpec spec;
  spec.nu = spec.nv = n;
  spec.size_u_m = spec.size_v_m = L;
  const ClothMesh mesh = make_grid(spec);
  const HingeBending hinges(mesh, m);
  for (bool along_warp : {true, false}) {
    const Matrix3X x = test::bent_into_cylinder(mesh, kappa, along_warp);
    double arcsim = 0.0;
    for (const Hinge& h : hinges.hinges()) {
      const auto X = [&](int k) { return Vec3(mesh.rest_positions.row(h.v[k]).transpose()); };
      const auto P = [&](int k) { return Vec3(x.row(h.v[k]).transpose()); };
      const Vec2 du = mesh.material_coords[h.v[1]] - mesh.material_coords[h.v[0]];
      const double ke = std::abs(du.y()) < 1e-12   ? f.bending[0]
                        : std::abs(du.x()) < 1e-12 ? f.bending[2]
                                                   : f.bending[1];
      const double l = (X(1) - X(0)).norm();
      const double a = 0.5 * ((X(1) - X(0)).cross(X(2) - X(0)).norm() +
                              (X(3) - X(0)).cross(X(1) - X(0)).norm());
      const double theta = hinge_angle(P(0), P(1), P(2), P(3));
      arcsim += 0.5 * ke * (l * l / (2.0 * a)) * theta * theta / 4.0;  // half weight
    }
    SCOPED_TRACE(along_warp ? "along warp" : "along weft");
    EXPECT_GT(arcsim, 0.0);
    EXPECT_NEAR(hinges.energy(x) / arcsim, 1.0, 1e-9);
  }
}

// Every preset: a source, finite positive values, and (all of them now) published throughout,
// with no drape coefficient claimed that its source does not give.
TEST(MaterialPresets, EveryPresetIsPublishedFiniteAndPositive) {
  EXPECT_GE(material_presets().size(), 9u);
  for (const MaterialPreset& p : material_presets()) {
    SCOPED_TRACE(p.name);
    const Material& m = p.material;
    for (double v : {m.density_kg_m2, m.stretch_warp_N_m, m.stretch_weft_N_m, m.shear_N_m,
                     m.bend_warp_Nm, m.bend_weft_Nm}) {
      EXPECT_TRUE(std::isfinite(v));
      EXPECT_GT(v, 0.0);
    }
    EXPECT_FALSE(p.source.empty());
    EXPECT_TRUE(p.fully_published());
    EXPECT_TRUE(p.representative_fields.empty());
    EXPECT_FALSE(p.drape_coefficient.has_value());
    EXPECT_NE(p.source.find("no drape coefficient"), std::string::npos) << p.source;
    if (p.name.rfind("wang2011_", 0) == 0) {
      EXPECT_NE(p.source.find("Wang, Ramamoorthi & O'Brien 2011"), std::string::npos);
      EXPECT_NE(p.source.find(".json"), std::string::npos);
    }
  }
}

double mean_bending_length_cm(const std::string& name) {
  const Material& m = material_preset(name).material;
  return std::sqrt(bending_length_cm(m.bend_warp_Nm, m.density_kg_m2) *
                   bending_length_cm(m.bend_weft_Nm, m.density_kg_m2));
}

// Peirce bending lengths of garment fabrics lie between about 1 and 5 cm; the data order them:
// the polycotton pants fabric (royal-target) is the stiffest, the t-shirt interlock the softest, the denim
// stiffer than the interlock in both directions. The knits stretch far more easily than the
// woven polyester and polycotton (tens of N/m against thousands: Wang et al.'s data).
TEST(MaterialPresets, BendingLengthsSpanGarmentFabricsInThePublishedOrder) {
  std::string softest, stiffest;
  for (const MaterialPreset& p : material_presets()) {
    if (p.material.bend_law_warp) continue;  // the "_curves" presets: MaterialPresets.CurvesPresets…
    const Material& m = p.material;
    for (double B : {m.bend_warp_Nm, m.bend_weft_Nm}) {
      EXPECT_GT(bending_length_cm(B, m.density_kg_m2), 1.0) << p.name;
      EXPECT_LT(bending_length_cm(B, m.density_kg_m2), 5.0) << p.name;
    }
    if (softest.empty() || mean_bending_length_cm(p.name) < mean_bending_length_cm(softest))
      softest = p.name;
    if (stiffest.empty() || mean_bending_length_cm(p.name) > mean_bending_length_cm(stiffest))
      stiffest = p.name;
  }
  EXPECT_EQ(softest, "wang2011_gray_interlock");
  EXPECT_EQ(stiffest, "wang2011_royal_target");
  EXPECT_GT(mean_bending_length_cm(stiffest), 1.5 * mean_bending_length_cm(softest));
  const Material& denim = material_preset("wang2011_11oz_black_denim").material;
  const Material& tshirt = material_preset("wang2011_gray_interlock").material;
  for (auto bend : {&Material::bend_warp_Nm, &Material::bend_weft_Nm})
    EXPECT_GT(peirce_bending_length_m(denim.*bend, denim.density_kg_m2, 9.81),
              peirce_bending_length_m(tshirt.*bend, tshirt.density_kg_m2, 9.81));
  for (const char* knit : {"wang2011_gray_interlock", "wang2011_navy_sparkle_sweat"})
    for (const char* woven : {"wang2011_royal_target", "wang2011_white_dots_on_blk"})
      EXPECT_GT(material_preset(woven).material.stretch_warp_N_m,
                20.0 * material_preset(knit).material.stretch_warp_N_m)
          << woven << " / " << knit;
}

// The softest and the stiffest preset as Peirce cantilevers (tests/sim/cantilever_support.h;
// Baraff–Witkin, which takes a shear rigidity above the stretch one): hung at the same 3 cm
// overhang the interlock droops further than the pants fabric, and each at its own O = 2c shows
// Peirce's 41.5° chord within the cantilever test's ±2.1°.
TEST(MaterialPresets, SoftestAndStiffestCantileversOrderAsTheirBendingLengths) {
  using namespace cantilever;  // NOLINT: the strip and its helpers
  const Material& soft = material_preset("wang2011_gray_interlock").material;
  const Material& stiff = material_preset("wang2011_royal_target").material;
  const ClothModel bw = ClothModel::baraff_witkin;
  const double soft_deg = hang_strip(soft, StripAlong::warp, 0.03, 8, bw).chord_deg();
  const double stiff_deg = hang_strip(stiff, StripAlong::warp, 0.03, 8, bw).chord_deg();
  std::printf("3 cm cantilever chord: gray interlock %.1f deg, royal target %.1f deg\n", soft_deg,
              stiff_deg);
  EXPECT_GT(soft_deg, stiff_deg + 10.0);
  for (const Material* m : {&soft, &stiff}) {
    const double c = bending_length(*m, StripAlong::warp);
    const double deg = hang_strip(*m, StripAlong::warp, 2.0 * c, 8, bw).chord_deg();
    std::printf("O = 2c = %.2f cm: chord %.1f deg (Peirce 41.5)\n", 200.0 * c, deg);
    EXPECT_NEAR(deg, 41.5, 2.1);
  }
}

// The mass-spring model with stretch springs puts the shear rigidity on diagonal springs that also
// stretch, so on square cells it needs shear < both stretch rigidities (MassSpringModel); two knits
// measure a shear rigidity above a stretch one (interlock 36.9 > 33.2 N/m warp; sweater 17.6 >
// 6.5 N/m weft) and it refuses them with a MaterialError, as it should. The continuum models build
// every linear preset, and so does the mass-spring model with stretch left to constraints. The
// "_curves" presets only build the mass-spring model with its springs (their laws need it); their
// rigidity at rest is the curves' slope at zero (their first mean slope, to 1e-4 strain), near
// the linear presets' (twice row 0), so the same two knits are refused.
TEST(MaterialPresets, EveryPresetBuildsTheContinuumModelsAndTheMassSpringWhereItCan) {
  GridSpec spec;
  spec.nu = spec.nv = 5;
  const ClothMesh mesh = make_grid(spec);
  std::set<std::string> refused;
  for (const MaterialPreset& p : material_presets()) {
    const Material& m = p.material;
    const bool curves = m.stretch_law_warp.has_value();
    for (ClothModel model : {ClothModel::baraff_witkin, ClothModel::rft3}) {
      if (curves) {
        EXPECT_THROW((void)make_force_terms(mesh, m, model, true), MaterialError) << p.name;
      } else {
        EXPECT_NO_THROW((void)make_force_terms(mesh, m, model, true)) << p.name;
      }
    }
    if (m.shear_N_m < std::min(m.stretch_warp_N_m, m.stretch_weft_N_m)) {
      const MassSpringModel model(mesh, m);
      for (const Spring& s : model.springs()) EXPECT_GT(s.k_N_m, 0.0) << p.name;
      for (const AngularSpring& b : model.bends()) EXPECT_GT(b.k_Nm, 0.0) << p.name;
    } else {
      EXPECT_THROW(MassSpringModel(mesh, m), MaterialError) << p.name;
      if (!curves) {
        EXPECT_NO_THROW(MassSpringModel(mesh, m, false)) << p.name;
      }
      refused.insert(p.name);
    }
  }
  EXPECT_EQ(refused, (std::set<std::string>{"wang2011_gray_interlock", "wang2011_navy_sparkle_sweat",
                                            "wang2011_gray_interlock_curves",
                                            "wang2011_navy_sparkle_sweat_curves"}));
}

// Each of the ten fabrics has a "_curves" preset: the linear one's density and shear, with both
// directions' tension–strain and moment–curvature laws, whose slopes at zero are its rigidities.
TEST(MaterialPresets, CurvesPresetsCarryBothLawsOfEachWangFabric) {
  int curves = 0;
  for (const MaterialPreset& p : material_presets()) {
    const Material& m = p.material;
    if (!m.stretch_law_warp) continue;
    ++curves;
    const std::string linear = p.name.substr(0, p.name.size() - std::string("_curves").size());
    ASSERT_EQ(p.name, linear + "_curves");
    const Material& base = material_preset(linear).material;
    EXPECT_EQ(m.density_kg_m2, base.density_kg_m2);
    EXPECT_EQ(m.shear_N_m, base.shear_N_m);
    ASSERT_TRUE(m.stretch_law_weft && m.bend_law_warp && m.bend_law_weft) << p.name;
    EXPECT_EQ(m.stretch_warp_N_m, m.stretch_law_warp->initial_stiffness());
    EXPECT_EQ(m.stretch_weft_N_m, m.stretch_law_weft->initial_stiffness());
    EXPECT_EQ(m.bend_warp_Nm, m.bend_law_warp->initial_rigidity());
    EXPECT_EQ(m.bend_weft_Nm, m.bend_law_weft->initial_rigidity());
    EXPECT_NE(p.source.find("tension against strain"), std::string::npos) << p.source;
  }
  EXPECT_EQ(curves, 10);
}

}  // namespace
}  // namespace weft::sim
