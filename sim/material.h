#pragma once
// Fabric parameters in SI units, per unit width/area so that they do not depend on the mesh.

namespace weft::sim {

// Defaults: the Kang & Yu wool of seed 002 (§4.1), converted from textile units.
struct Material {
  double density_kg_m2 = 0.19;       // areal density (a weight of 0.019 gf/cm² is 0.19 kg/m²)
  double stretch_warp_N_m = 1096.6;  // tensile rigidity along warp (u): force per width per unit strain
  double stretch_weft_N_m = 744.8;   // tensile rigidity along weft (v)
  double shear_N_m = 41.0;           // in-plane shear rigidity, per unit shear strain (radian)
  double bend_warp_Nm = 8.14e-6;     // bending rigidity, curvature along warp: moment per width per curvature
  double bend_weft_Nm = 6.18e-6;     // bending rigidity along weft (0.063 gf·cm = 6.18e-6 N·m)
};

}  // namespace weft::sim
