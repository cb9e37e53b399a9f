#pragma once
// Air acting on the cloth: a wind field and the drag of each triangle moving through it.
//
// Drag on a thin plate is dominated by the pressure on its faces (Hoerner, "Fluid-Dynamic
// Drag", 1965, ch. 3: a flat plate normal to the flow has C_d ≈ 1.17; skin friction along it
// is two orders smaller and is left out). Each warp/weft quad — a panel with vector area
// A n = ½ (x2 − x0) × (x3 − x1) (exact for a planar quad, the projected area of a warped one) —
// moving with the mean velocity v of its corners through air of density ρ moving with the
// wind u at its centre, feels
//   f = −½ ρ C_d A |w_n| w_n n,   w_n = (v − u) · n,
// shared equally by its four corners, as the lumped masses share the quad's mass; so drag per
// mass is the same at every vertex of a flat sheet, boundary included. (Sharing a triangle's
// drag by thirds gives a grid corner 4/3 or 2/3 of its mass share and curls a falling sheet:
// measured, 36–45 % above the terminal speed.) Only the normal relative velocity counts, so a sheet
// sliding edge-on through still air feels nothing, and the force does not depend on which side
// the normal points to. A horizontal sheet falling flat reaches the terminal speed
// √(2 ρ_A g / (ρ C_d)), ρ_A its areal density (tests/sim/aerodynamics_test.cpp).
//
// The wind is a uniform velocity U with an optional travelling gust along it:
//   u(x, t) = U (1 + a sin(2π (t/T − x·Û/λ)))
// with amplitude a (fraction of U), period T and wavelength λ (λ = 0: the same at every point).

#include <array>
#include <string>
#include <vector>

#include "sim/force_term.h"
#include "sim/types.h"

namespace weft::sim {

struct Gust {
  double amplitude = 0.0;     // fraction of the mean wind speed, ≥ 0
  double period_s = 1.0;      // > 0
  double wavelength_m = 0.0;  // ≥ 0; 0: uniform in space
};

struct WindField {
  Vec3 velocity_m_s = Vec3::Zero();  // mean wind U
  Gust gust;
  // u(x, t), m/s.
  Vec3 at(const Vec3& x_m, double time_s) const;
};

struct AeroSettings {
  bool enabled = false;            // no aerodynamic term at all unless the scene asks
  double air_density_kg_m3 = 1.2;  // dry air near 20 °C at sea level
  double drag_coefficient = 1.17;  // flat plate normal to the flow (Hoerner)
  WindField wind;
};

// The drag force on a flat panel of vector area A n (m², either orientation) moving with
// relative_velocity through the air: N, for the whole panel. Zero for a zero area.
inline Vec3 panel_drag_force(const Vec3& area_vector_m2, const Vec3& relative_velocity_m_s,
                             double air_density_kg_m3, double drag_coefficient) {
  const double area = area_vector_m2.norm();
  if (area == 0.0) return Vec3::Zero();
  const Vec3 n = area_vector_m2 / area;
  const double wn = relative_velocity_m_s.dot(n);
  return (-0.5 * air_density_kg_m3 * drag_coefficient * area * std::abs(wn) * wn) * n;
}

// The vector area ½ (x2 − x0) × (x3 − x1) of a quad with corners x0..x3 in order.
inline Vec3 quad_area_vector(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  return 0.5 * (x2 - x0).cross(x3 - x1);
}

// The drag of every quad as a System's velocity-dependent force term.
class Aerodynamics final : public VelocityForceTerm {
 public:
  Aerodynamics(std::vector<std::array<Index, 4>> quads, const AeroSettings& settings);
  // Quads and triangles (a cloth mesh without a grid): a triangle panel's drag is shared by
  // its three corners, as its lumped mass is.
  Aerodynamics(std::vector<std::array<Index, 4>> quads, std::vector<std::array<Index, 3>> triangles,
               const AeroSettings& settings);

  // "air drag on 16 quads (C_d 0.9, 1.1 kg/m³, wind 3 m/s gusting ±25 % every 2 s)"
  std::string describe() const override;
  // f += the drag on every quad at positions x (m), velocities v (m/s), time t (s).
  void add_forces(const Matrix3X& x, const Matrix3X& v, double time_s, Matrix3X& f) const override;
  const AeroSettings& settings() const { return m_settings; }
  std::size_t panel_count() const { return m_quads.size() + m_triangles.size(); }

 private:
  std::vector<std::array<Index, 4>> m_quads;
  std::vector<std::array<Index, 3>> m_triangles;
  AeroSettings m_settings;
};

}  // namespace weft::sim
