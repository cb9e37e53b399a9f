#pragma once
// The ten fabrics measured by Wang, Ramamoorthi and O'Brien (2011), "Data-Driven Elastic Models
// for Cloth: Modeling and Measurement", ACM Trans. Graph. 30(4) 71, every number of the model
// files ARCSim distributes (materials/<fabric>.json), and the measured curves they hold: tension
// against strain along u and v, and bending moment against curvature along u and v. How ARCSim's
// code reads each number: assets/fabrics/README.md and arcsim_materials.json, "interpretation".

#include <string>
#include <vector>

#include "sim/material/bending_law.h"
#include "sim/material/stretch_law.h"

namespace weft::sim {

struct Wang2011Fabric {
  std::string preset;  // weft's preset name, "wang2011_11oz_black_denim"
  std::string file;    // ARCSim's file name, "11oz-black-denim"
  std::string what;    // its use and fibre content (ARCSim's materials/README)
  double density_kg_m2 = 0.0;
  // "stretching": halves (c11, c12, c22, c33) of the stiffness, N/m; row 0 at no stretch, rows
  // 1–5 at a largest principal stretch of 7/6 along 0°, 22.5°, 45°, 67.5°, 90° from u.
  double stretching[6][4] = {};
  // "bending": the hinge coefficient ke, N·m; row 0 for hinge edges along u, 1 at 45°, 2 along
  // v; column j at curvature κ = 10 j m⁻¹.
  double bending[3][5] = {};
};

// All ten, in ARCSim's (alphabetical) order.
const std::vector<Wang2011Fabric>& wang2011_fabrics();

enum class FabricAxis { u, v };

// The tension per width against engineering strain ε of a strip stretched along `axis` with no
// lateral strain, as ARCSim's model of the fabric gives it (the derivation is at the definition):
// T(ε) = λ k(λ) (λ² − 1)/2 with λ = 1 + ε, k = 2 max(0, row 0 + s (row r − row 0)),
// s = min(1, 6 ε), r the row stretched along the axis (1 for u, 5 for v), column c11 (u) or c22
// (v). A table sampled at 1e-4, 1e-3, every 1/60 of strain to 1/6, then at 0.2, 0.25, 0.3, 0.4, 0.5.
StretchLaw wang2011_stretch_law(const Wang2011Fabric& fabric, FabricAxis axis);

// The bending moment per width against curvature κ along `axis`: M(κ) = (ke(κ)/4) κ, ke
// interpolated linearly in κ between columns 0–3 (κ = 0…30 m⁻¹) of row 2 (u) or row 0 (v). Column
// 4 (40 m⁻¹) is left out: with it the moment falls for 24 of the 30 rows, a bending curve with no
// stable fold, most likely past the curvatures measured. A table sampled at 0.25 m⁻¹ and every 2.5 m⁻¹ to 30 m⁻¹,
// continued with its last slope.
BendingLaw wang2011_bending_law(const Wang2011Fabric& fabric, FabricAxis axis);

}  // namespace weft::sim
