#include "sim/material_presets.h"

#include <cmath>
#include <stdexcept>

namespace weft::sim {
namespace {

using textile::gf_cm;
using textile::gf_per_cm;
using textile::gf_per_cm2;

// Arguments in textile units: weight gf/cm²; tensile warp, weft and shear rigidity gf/cm (shear
// per radian: KES's G in gf/(cm·deg) × 180/π); bending warp, weft gf·cm.
Material textile_material(double weight, double stretch_warp, double stretch_weft, double shear,
                          double bend_warp, double bend_weft) {
  Material m;
  m.density_kg_m2 = gf_per_cm2(weight);
  m.stretch_warp_N_m = gf_per_cm(stretch_warp);
  m.stretch_weft_N_m = gf_per_cm(stretch_weft);
  m.shear_N_m = gf_per_cm(shear);
  m.bend_warp_Nm = gf_cm(bend_warp);
  m.bend_weft_Nm = gf_cm(bend_weft);
  return m;
}

// Luible, C. (2008), "Study of mechanical properties in the simulation of 3D garments", PhD thesis
// no. 678, University of Geneva (MIRALab), doi:10.13097/archive-ouverte/unige:688, Annex G "Linear
// derived fabric input parameters" (thesis pp. 231-236). Luible measured apparel fabrics (numbered
// 01 to at least 34) with KES-F and derived from them the linear inputs of a cloth simulator (SI):
// weight in g/m², tensile rigidity ("Elasticity") along weft and warp in N/m (force per width per
// unit strain) and shear rigidity in N/m per unit shear strain — her Annex F converts KES's
// G [gf/(cm·deg)] to it with G(tan θ) = 57.3 G(θ in degrees). These are Luible's derived (rounded)
// simulator inputs, not raw KES characteristic values. The thesis PDF was not readable here: the
// numbers below are as transcribed, with their fabric numbers and table cells, in the GPL Blender
// add-on GPUCloth (github.com/PorisulkiP/GPUCloth, GPUCloth/Cpp_Compatibility/properties.py,
// FABRIC_PRESETS "LUI_*", one stored version), which maps Annex G's column order "Weft, Warp,
// Shear" to warp/weft as used here and checks the shear column against the thesis text (flannel:
// "118.13 N/m (mean value of weft and warp G(tan θ))" = its Annex G cell).
//
// Bending rigidity: Annex G has bending columns (µN·m), but the transcription leaves them out and
// no other published warp/weft bending rigidity of these fabrics was found. The bending rigidities
// below are therefore NOT measurements: they are representative values, B = W c³ (Peirce's
// cantilever bending length c, B in gf·cm for W in gf/cm² and c in cm), with the measured weight W
// and a bending length c typical of the fabric class chosen by weft (the rounded c of weft's earlier
// representative presets: 1.80/1.61, 1.26/1.19, 3.35/2.82 cm). Replace them (material keys override a preset one by one) by measured
// values when bending matters.
constexpr const char* representative_bending = "bend_warp, bend_weft";

// A Luible Annex G fabric: weight in g/m², tensile warp and weft and shear rigidity in N/m (shear
// per unit shear strain), and the representative bending lengths in cm (see above).
Material luible_material(double weight_g_m2, double stretch_warp_N_m, double stretch_weft_N_m,
                         double shear_N_m, double bending_length_warp_cm,
                         double bending_length_weft_cm) {
  const double weight_gf_cm2 = weight_g_m2 * 1e-4;  // 1 g/m² = 1e-4 g/cm², weighing 1e-4 gf/cm²
  Material m;
  m.density_kg_m2 = gf_per_cm2(weight_gf_cm2);
  m.stretch_warp_N_m = stretch_warp_N_m;
  m.stretch_weft_N_m = stretch_weft_N_m;
  m.shear_N_m = shear_N_m;
  m.bend_warp_Nm = gf_cm(weight_gf_cm2 * std::pow(bending_length_warp_cm, 3));
  m.bend_weft_Nm = gf_cm(weight_gf_cm2 * std::pow(bending_length_weft_cm, 3));
  return m;
}

std::string luible_source(const std::string& fabric) {
  return "Luible 2008, PhD thesis no. 678, Univ. of Geneva, 'Study of mechanical properties in the "
         "simulation of 3D garments', Annex G, " +
         fabric +
         ": weight, tensile warp/weft and shear rigidity (as transcribed in GPUCloth's "
         "properties.py; thesis table not checked here). Bending: no published value found, "
         "representative (B = W c^3 with a typical bending length c); no drape coefficient "
         "given";
}

std::vector<MaterialPreset> make_presets() {
  return {
      // Exact published values: Kang, T. J. and Yu, W. R. (1995), "Drape simulation of woven
      // fabric by using the finite-element method", Journal of the Textile Institute; as quoted in
      // seed 002 (Zhou & Sze), §4: tensile 1118.2 / 759.5 gf/cm, shear 41.8 gf/cm, bending
      // 0.083 / 0.063 gf·cm, weight 0.019 gf/cm² (the table number in Kang & Yu was not checked).
      // Bending length c = 1.635 cm warp, 1.491 cm weft (tests/sim/cantilever_test.cpp).
      // Drape coefficient: the quoting source gives none (Kang & Yu's own measured drape, if
      // any, was not available here).
      {"wool_kang_yu", textile_material(0.019, 1118.2, 759.5, 41.8, 0.083, 0.063),
       "Kang & Yu 1995, J. Textile Inst., 'Drape simulation of woven fabric by using the "
       "finite-element method', as quoted in seed 002 (Zhou & Sze) section 4 (table number "
       "not checked); no drape coefficient given",
       "", std::nullopt},
      // Luible fabric 02, cotton shirting, 120 g/m²: tensile 2000 (warp) / 3000 (weft) N/m, shear
      // 20 N/m. Representative bending lengths 1.8 / 1.6 cm → B = 0.0700 / 0.0492 gf·cm.
      {"cotton_shirting", luible_material(120.0, 2000.0, 3000.0, 20.0, 1.8, 1.6),
       luible_source("fabric 02, cotton shirting 120 g/m^2"), representative_bending,
       std::nullopt},
      // Luible fabric 07, mulberry silk, 15 g/m² (a very light silk): tensile 6000 (warp) / 4500
      // (weft) N/m, shear 10 N/m. Representative bending lengths 1.25 / 1.2 cm →
      // B = 0.0029 / 0.0026 gf·cm.
      {"silk_mulberry", luible_material(15.0, 6000.0, 4500.0, 10.0, 1.25, 1.2),
       luible_source("fabric 07, mulberry silk 15 g/m^2"), representative_bending,
       std::nullopt},
      // Luible fabric 01, denim, 380 g/m²: tensile 1800 (warp) / 3000 (weft) N/m, shear 102 N/m.
      // Representative bending lengths 3.35 / 2.8 cm → B = 1.43 / 0.83 gf·cm.
      {"denim", luible_material(380.0, 1800.0, 3000.0, 102.0, 3.35, 2.8),
       luible_source("fabric 01, denim 380 g/m^2"), representative_bending, std::nullopt},
  };
}

}  // namespace

double peirce_bending_length_m(double bend_Nm, double density_kg_m2, double gravity_m_s2) {
  if (!(std::isfinite(bend_Nm) && bend_Nm >= 0.0))
    throw std::invalid_argument("peirce_bending_length_m: bending rigidity must be finite and >= 0");
  if (!(std::isfinite(density_kg_m2) && density_kg_m2 > 0.0))
    throw std::invalid_argument("peirce_bending_length_m: areal density must be finite and > 0");
  if (!(std::isfinite(gravity_m_s2) && gravity_m_s2 > 0.0))
    throw std::invalid_argument("peirce_bending_length_m: gravity must be finite and > 0");
  return std::cbrt(bend_Nm / (density_kg_m2 * gravity_m_s2));
}

const std::vector<MaterialPreset>& material_presets() {
  static const std::vector<MaterialPreset> presets = make_presets();
  return presets;
}

std::vector<std::string> material_preset_names() {
  std::vector<std::string> names;
  for (const MaterialPreset& p : material_presets()) names.push_back(p.name);
  return names;
}

const MaterialPreset& material_preset(const std::string& name) {
  for (const MaterialPreset& p : material_presets())
    if (p.name == name) return p;
  std::string known;
  for (const std::string& n : material_preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown material preset '" + name + "' (known: " + known + ")");
}

}  // namespace weft::sim
