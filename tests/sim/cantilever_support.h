#pragma once
// The Peirce cantilever strip of tests/sim/cantilever_test.cpp (the reading of the clamp edge
// and the reference values are explained there), shared with the dynamic relaxation test: the
// strip, its clamp, the tip drop of a solved strip, and the damped implicit Euler solve to rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/constants.h"
#include "sim/simulator.h"

namespace weft::sim::cantilever {

// Kang & Yu's wool: sim::Material's defaults.
inline const Material kWool{};

enum class StripAlong { warp, weft };

struct Bent {
  double drop_m = 0.0;        // clamp edge height − tip height
  double horizontal_m = 0.0;  // from the clamp edge to the tip, along the strip
  double chord_deg() const { return std::atan2(drop_m, horizontal_m) * 180.0 / base::kPi; }
};

inline double bending_rigidity(const Material& m, StripAlong along) {
  return along == StripAlong::warp ? m.bend_warp_Nm : m.bend_weft_Nm;
}

// Weight per area, N/m².
inline double areal_weight(const Material& m, const SimSettings& s) {
  return m.density_kg_m2 * s.gravity_m_s2.norm();
}

inline double bending_length(const Material& m, StripAlong along) {
  return std::cbrt(bending_rigidity(m, along) / areal_weight(m, SimSettings{}));
}

// The overhang at which w O³ / B = λ.
inline double overhang_for(double lambda, const Material& m, StripAlong along) {
  return bending_length(m, along) * std::cbrt(lambda);
}

// A strip `width_m` wide (1 cm like Kang & Yu's 1 × 5 cm strip, seed 002 §4.1: the width does not
// enter the beam theory, and a narrow strip keeps the test fast), overhanging by `overhang_m` in
// `segments` free cells beyond the clamp; its first two vertex lines across are clamped.
struct Strip {
  StripAlong along = StripAlong::warp;
  ClothMesh mesh;
  std::vector<Index> clamped;  // sorted
  Index n_long = 0, n_across = 0;
  double cell_u_m = 0.0, cell_v_m = 0.0;  // grid cell sizes along u and v
  Index vertex(Index along_k, Index across_k) const {
    return along == StripAlong::warp ? mesh.index(along_k, across_k)
                                     : mesh.index(across_k, along_k);
  }
};

inline Strip make_strip(StripAlong along, double overhang_m, Index segments,
                        double width_m = 0.01) {
  Strip s;
  s.along = along;
  const double h = overhang_m / (static_cast<double>(segments) + 0.5);  // clamp edge mid-cell
  s.n_long = segments + 2;
  // Across, cells at most 3× longer than along: the shear springs would otherwise exceed the
  // stretch stiffness across (MassSpringModel's aspect-ratio check).
  s.n_across = std::max<Index>(2, static_cast<Index>(std::ceil(width_m / (3.0 * h))) + 1);
  const double h_across = width_m / static_cast<double>(s.n_across - 1);

  GridSpec grid;
  grid.origin = Vec3(0.0, 0.0, 0.5);
  if (along == StripAlong::warp) {
    grid.nu = s.n_long;
    grid.nv = s.n_across;
    grid.size_u_m = h * static_cast<double>(s.n_long - 1);
    grid.size_v_m = width_m;
    grid.warp_axis = Vec3::UnitX();
    grid.weft_axis = Vec3::UnitY();
  } else {
    grid.nu = s.n_across;
    grid.nv = s.n_long;
    grid.size_u_m = width_m;
    grid.size_v_m = h * static_cast<double>(s.n_long - 1);
    grid.warp_axis = -Vec3::UnitY();
    grid.weft_axis = Vec3::UnitX();
  }
  s.mesh = make_grid(grid);
  s.cell_u_m = along == StripAlong::warp ? h : h_across;
  s.cell_v_m = along == StripAlong::warp ? h_across : h;
  for (Index a = 0; a < s.n_across; ++a)
    for (Index k : {0, 1}) s.clamped.push_back(s.vertex(k, a));
  std::sort(s.clamped.begin(), s.clamped.end());
  return s;
}

// The clamp edge (midway between lines 0 and 1) and the tip, averaged across the strip.
inline Bent measure(const Strip& s, const Matrix3X& x) {
  Vec3 edge = Vec3::Zero(), tip = Vec3::Zero();
  for (Index a = 0; a < s.n_across; ++a) {
    edge += 0.5 * (x.row(s.vertex(0, a)) + x.row(s.vertex(1, a))).transpose();
    tip += x.row(s.vertex(s.n_long - 1, a)).transpose();
  }
  edge /= static_cast<double>(s.n_across);
  tip /= static_cast<double>(s.n_across);
  return {edge.z() - tip.z(), tip.x() - edge.x()};
}

// The first cantilever mode, ω1 = 1.875² √(B / (ρ O⁴)), rad/s.
inline double first_mode_rad_s(const Material& material, StripAlong along, double overhang_m) {
  return 3.516 * std::sqrt(bending_rigidity(material, along) /
                           (material.density_kg_m2 * std::pow(overhang_m, 4)));
}

// The strip solved to static equilibrium by damped implicit Euler; `steps` (if given) gets the
// number of time steps it took.
inline Bent hang_strip(const Material& material, StripAlong along, double overhang_m,
                       Index segments, ClothModel model = ClothModel::mass_spring,
                       double width_m = 0.01, long* steps = nullptr) {
  const Strip strip = make_strip(along, overhang_m, segments, width_m);
  SimSettings settings;
  settings.model = model;
  settings.integrator = Integrator::implicit_euler;
  // Bending is explicit in implicit Euler: stay below its critical step, 2/ω with
  // ω² ≤ 16 B / (ρ h⁴) (the Gershgorin bound of docs/models.md for a bending stencil).
  const double omega_bend =
      std::sqrt(16.0 *
                std::max(material.bend_warp_Nm / std::pow(strip.cell_u_m, 4),
                         material.bend_weft_Nm / std::pow(strip.cell_v_m, 4)) /
                material.density_kg_m2);
  settings.time_step = fixed_time_step(1.6 / omega_bend);
  // About critical damping of the first cantilever mode.
  const double omega1 = first_mode_rad_s(material, along, overhang_m);
  settings.air_damping_1_s = 2.0 * omega1;

  Simulator sim(strip.mesh, material, strip.clamped, settings);
  const double B = bending_rigidity(material, along);
  const double linear_drop = areal_weight(material, settings) * std::pow(overhang_m, 4) / (8.0 * B);
  const double energy_scale = sim.masses_kg().sum() * settings.gravity_m_s2.norm() * linear_drop;
  double t = 0.0;
  while (true) {
    sim.advance(1.0 / omega1);
    t += 1.0 / omega1;
    if (sim.diagnostics().kinetic_energy_J < 1e-9 * energy_scale) break;
    if (t > 60.0 / omega1) {
      ADD_FAILURE() << "the strip has not come to rest after " << t << " s";
      break;
    }
  }
  if (steps) *steps = sim.steps_taken();
  return measure(strip, sim.state().x);
}

}  // namespace weft::sim::cantilever
