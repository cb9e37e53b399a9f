#pragma once
// Fabric parameters in SI units, per unit width/area so that they do not depend on the mesh.

namespace weft::sim {

struct Material {
  double density_kg_m2 = 0.19;     // areal density (0.019 gf/cm² ≈ 0.186 kg/m²)
  double stretch_warp_N_m = 1096.6;  // tensile rigidity along warp (u): force per width per unit strain
  double stretch_weft_N_m = 744.8;   // tensile rigidity along weft (v)
  double shear_N_m = 41.0;           // in-plane shear rigidity, per unit shear strain (radian)
  double bend_warp_N_m = 8.1e-6;     // bending rigidity for curvature along warp: moment per width per curvature
  double bend_weft_N_m = 6.2e-6;     // bending rigidity along weft (0.063 gf·cm = 6.2e-6 N·m)
};

}  // namespace weft::sim
