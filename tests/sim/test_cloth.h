#pragma once
// Cloths shared by the simulation tests: a generic fabric scaled by its tensile rigidity, and a
// flat horizontal square grid.

#include <memory>
#include <vector>

#include "sim/grid.h"
#include "sim/mass_spring.h"
#include "sim/material/material.h"
#include "sim/system.h"

namespace weft::sim::test_cloth {

// Two vertices of mass m, kg, joined by a spring k, N/m, of rest length L, m: vertex 0 pinned,
// gravity g, m/s², along −z. Its static extension is m g / k.
inline System hanging_spring(double m, double k, double L, double g) {
  System system;
  system.terms.push_back(
      std::make_shared<SpringTerm>(std::vector<Spring>{{0, 1, L, k, SpringKind::warp}}));
  system.mass_kg = Eigen::Vector2d(m, m);
  system.inv_mass = Eigen::Vector2d(0.0, 1.0 / m);
  system.gravity_m_s2 = Vec3(0.0, 0.0, -g);
  return system;
}

// Tensile rigidity stretch_N_m along warp, 0.7× along weft, shear 5 % of it, 0.2 kg/m².
inline Material fabric(double stretch_N_m) {
  Material m;
  m.density_kg_m2 = 0.2;
  m.stretch_warp_N_m = stretch_N_m;
  m.stretch_weft_N_m = 0.7 * stretch_N_m;
  m.shear_N_m = 0.05 * stretch_N_m;
  m.bend_warp_Nm = 1e-5;
  m.bend_weft_Nm = 8e-6;
  return m;
}

// n×n vertices over size_m × size_m, horizontal, material (0, 0) at `origin`.
inline ClothMesh square(Index n, double size_m = 1.0, Vec3 origin = Vec3(0, 0, 2)) {
  GridSpec spec;
  spec.size_u_m = spec.size_v_m = size_m;
  spec.nu = spec.nv = n;
  spec.origin = origin;
  return make_grid(spec);
}

}  // namespace weft::sim::test_cloth
