#pragma once
// Named fabrics: a name → Material lookup for scene files ("cloth.material.preset") and tests.
// Each preset says where its numbers come from, and which of them are not from that source;
// docs/scene.md lists them with their sources.

#include <optional>
#include <string>
#include <vector>

#include "sim/material/material.h"

namespace weft::sim {

struct MaterialPreset {
  std::string name;    // e.g. "wool_kang_yu"
  Material material;   // SI units
  std::string source;  // the publication (and table) the numbers come from
  // The Material fields that are NOT from `source` but representative values chosen by weft
  // (e.g. "bend_warp, bend_weft"); empty when every field is published. `source` says why.
  std::string representative_fields;
  // The Cusick drape coefficient (Cusick 1968: 30 cm specimen on an 18 cm disc) that `source`
  // publishes for this fabric, dimensionless in [0, 1]; empty when the source gives none.
  std::optional<double> drape_coefficient;

  // True when every Material field is from `source` (no representative value).
  bool fully_published() const { return representative_fields.empty(); }
};

// Peirce's cantilever bending length c = (B/w)^(1/3), m, of a fabric of bending rigidity B
// (N·m, moment per width per curvature) and areal density ρ (kg/m²) under gravity g (m/s²):
// w = ρ·g is its weight per area (N/m²). Peirce, F. T. (1930), "The 'handle' of cloth as a
// measurable quantity", J. Textile Inst. 21, T377; the ASTM D1388 cantilever measures c, and a
// published c gives B = w·c³. Throws std::invalid_argument unless B ≥ 0 and ρ, g > 0 (finite).
double peirce_bending_length_m(double bend_Nm, double density_kg_m2, double gravity_m_s2);

// One fabric as ARCSim's material file gives the measurements of Wang, Ramamoorthi and O'Brien
// (2011), "Data-Driven Elastic Models for Cloth: Modeling and Measurement", ACM Trans. Graph.
// 30(4) 71 (the files materials/<fabric>.json of ARCSim): only the small-deformation samples,
// which are what a linear weft Material can hold. ARCSim's u is its material's first axis.
struct ArcsimFabric {
  double density_kg_m2 = 0.0;  // "density": mass per area (ARCSim: node mass = density × area)
  // "stretching"[0], the strain-0 sample, N/m: {c11/2, c12/2, c22/2, c33/2} of ARCSim's membrane
  // energy per area ½c11 ε_uu² + c12 ε_uu ε_vv + ½c22 ε_vv² + c33 ε_uv² (Green strain ε).
  double stretching[4] = {0.0, 0.0, 0.0, 0.0};
  // "bending"[r][0], the zero-curvature sample, N·m: ARCSim's hinge coefficient ke for hinge
  // edges along u (r = 0), at 45° (r = 1) and along v (r = 2).
  double bending[3] = {0.0, 0.0, 0.0};
};

// The linear weft Material of an ArcsimFabric (the derivation is at the definition):
//   stretch_warp = 2·stretching[0], stretch_weft = 2·stretching[2], shear = stretching[3],
//   bend_warp = bending[2] / 4, bend_weft = bending[0] / 4,
// warp/weft being ARCSim's u/v. Throws std::invalid_argument unless the density and every value
// used is finite and > 0 (the c12 coupling and the 45° bending sample have no weft field).
Material material_from_arcsim(const ArcsimFabric& fabric);

// All presets, in a fixed order (the first is sim::Material's default).
const std::vector<MaterialPreset>& material_presets();

// Their names, in the same order.
std::vector<std::string> material_preset_names();

// The preset called `name`. Throws std::invalid_argument naming it and listing the known names:
// "unknown material preset 'wool' (known: wool_kang_yu, wang2011_11oz_black_denim, ...)".
const MaterialPreset& material_preset(const std::string& name);

}  // namespace weft::sim
