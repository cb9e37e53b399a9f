#pragma once
// Fabric parameters in SI units, per unit width/area so that they do not depend on the mesh.
// Named fabrics (presets) with their sources: sim/material/material_presets.h.

#include <optional>
#include <stdexcept>

#include "sim/material/bending_law.h"
#include "sim/material/stretch_law.h"

namespace weft::sim {

// A material the model cannot be built from (e.g. a negative rigidity, or shear springs stiffer
// than the stretch ones): bad input about the material, and only that. The scene reader labels
// these, and only these, with the material's key (app::make_simulator).
class MaterialError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Textile units, as KES and FAST report them, in SI. A weight is converted to a mass with
// standard gravity g0 = 9.80665 m/s² (docs/scene.md, "Units").
namespace textile {
inline constexpr double gram_force_N = 9.80665e-3;
// Tensile or shear rigidity in gf/cm → N/m.
constexpr double gf_per_cm(double value) {
  return value * gram_force_N / 1e-2;
}
// Bending rigidity in gf·cm (gf·cm²/cm) → N·m.
constexpr double gf_cm(double value) {
  return value * gram_force_N * 1e-2;
}
// Fabric weight in gf/cm² → areal density in kg/m² (1 gf/cm² weighs 1 g/cm² = 10 kg/m²).
constexpr double gf_per_cm2(double value) {
  return value * 1e-3 / 1e-4;
}
}  // namespace textile

// Defaults: the Kang & Yu wool of seed 002 (§4: Kang & Yu 1995, as quoted by Zhou & Sze), given
// in its textile units; the preset "wool_kang_yu" is this material.
struct Material {
  double density_kg_m2 = textile::gf_per_cm2(0.019);  // 0.19 kg/m²
  // Tensile rigidity along warp (u): force per width per unit strain. 1096.6 N/m.
  double stretch_warp_N_m = textile::gf_per_cm(1118.2);
  double stretch_weft_N_m = textile::gf_per_cm(759.5);  // along weft (v): 744.8 N/m
  // In-plane shear rigidity, per unit shear strain (radian). 41.0 N/m.
  double shear_N_m = textile::gf_per_cm(41.8);
  // Bending rigidity, curvature along warp: moment per width per curvature. 8.14e-6 N·m.
  double bend_warp_Nm = textile::gf_cm(0.083);
  double bend_weft_Nm = textile::gf_cm(0.063);  // along weft: 6.18e-6 N·m
  // Nonlinear bending (sim/material/bending_law.h), per direction; none: linear, M = B κ. When set,
  // bend_warp_Nm / bend_weft_Nm are its initial rigidity (the slope at κ = 0), which sets the
  // time step and the stability bounds. Only the mass-spring model on a grid bends by a law.
  std::optional<BendingLaw> bend_law_warp, bend_law_weft;
  // Nonlinear stretch (sim/material/stretch_law.h), per direction; none: linear, T = Y ε. When
  // set, stretch_warp_N_m / stretch_weft_N_m are its initial stiffness (the slope at ε = 0). Only
  // the mass-spring model's structural springs on a grid stretch by a law.
  std::optional<StretchLaw> stretch_law_warp, stretch_law_weft;
};

}  // namespace weft::sim
