#include "sim/material_presets.h"

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

// Representative values (cotton, silk, denim) are not the measurement of one fabric and cite no
// table: they are round numbers chosen by weft inside the usual range of their fabric class — a
// common trade weight, and a bending rigidity giving a typical cantilever bending length
// c = (B/W)^{1/3} (in cm for B in gf·cm and W in gf/cm²). The tensile and shear rigidities are
// order-of-magnitude values, of the form and size of Kang & Yu's; low-load tensile rigidity of
// woven fabric varies widely with crimp and test load. Replace them by measured values
// (material keys override a preset one by one) when a particular fabric matters.
const char* const representative =
    "representative values, not a measurement: chosen within the usual range of the fabric class";

std::vector<MaterialPreset> make_presets() {
  return {
      // Exact published values: Kang, T. J. and Yu, W. R. (1995), "Drape simulation of woven
      // fabric by using the finite-element method", Journal of the Textile Institute; as quoted in
      // seed 002 (Zhou & Sze), §4: tensile 1118.2 / 759.5 gf/cm, shear 41.8 gf/cm, bending
      // 0.083 / 0.063 gf·cm, weight 0.019 gf/cm² (the table number in Kang & Yu was not checked).
      // Bending length c = 1.635 cm warp, 1.491 cm weft (tests/sim/cantilever_test.cpp).
      {"wool_kang_yu", textile_material(0.019, 1118.2, 759.5, 41.8, 0.083, 0.063),
       "Kang & Yu 1995, J. Textile Inst., 'Drape simulation of woven fabric by using the "
       "finite-element method', as quoted in seed 002 (Zhou & Sze) section 4"},
      // Plain-weave cotton shirting, 120 g/m². Representative: shear 60 gf/cm ≈ 1.0 gf/(cm·deg);
      // c = (0.070 / 0.012)^{1/3} = 1.80 cm warp, 1.61 cm weft.
      {"cotton_shirting", textile_material(0.012, 1500.0, 1000.0, 60.0, 0.070, 0.050),
       representative},
      // Light silk (habotai), 60 g/m². Representative: shear 20 gf/cm ≈ 0.35 gf/(cm·deg);
      // c = (0.012 / 0.006)^{1/3} = 1.26 cm warp, 1.19 cm weft.
      {"silk_habotai", textile_material(0.006, 800.0, 600.0, 20.0, 0.012, 0.010), representative},
      // Heavy cotton denim, 400 g/m² (about 12 oz/yd²). Representative: shear 150 gf/cm
      // ≈ 2.6 gf/(cm·deg); c = (1.5 / 0.040)^{1/3} = 3.35 cm warp, 2.82 cm weft.
      {"denim", textile_material(0.040, 4000.0, 2500.0, 150.0, 1.5, 0.9), representative},
  };
}

}  // namespace

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
