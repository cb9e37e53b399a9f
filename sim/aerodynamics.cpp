#include "sim/aerodynamics.h"

#include <cmath>
#include <sstream>

namespace weft::sim {

Vec3 WindField::at(const Vec3& x_m, double time_s) const {
  if (gust.amplitude == 0.0) return velocity_m_s;
  constexpr double two_pi = 6.283185307179586;
  const double speed = velocity_m_s.norm();
  double phase = time_s / gust.period_s;
  if (gust.wavelength_m > 0.0 && speed > 0.0)
    phase -= x_m.dot(velocity_m_s / speed) / gust.wavelength_m;
  return velocity_m_s * (1.0 + gust.amplitude * std::sin(two_pi * phase));
}

Aerodynamics::Aerodynamics(std::vector<std::array<Index, 4>> quads, const AeroSettings& settings)
    : m_quads(std::move(quads)), m_settings(settings) {}

Aerodynamics::Aerodynamics(std::vector<std::array<Index, 4>> quads,
                           std::vector<std::array<Index, 3>> triangles, const AeroSettings& settings)
    : m_quads(std::move(quads)), m_triangles(std::move(triangles)), m_settings(settings) {}

std::string Aerodynamics::describe() const {
  const AeroSettings& a = m_settings;
  std::ostringstream line;
  line << "air drag on " << panel_count() << (m_triangles.empty() ? " quads" : " panels") << " (C_d " << a.drag_coefficient << ", "
       << a.air_density_kg_m3 << " kg/m³";
  if (a.wind.velocity_m_s.norm() > 0.0) {
    line << ", wind " << a.wind.velocity_m_s.norm() << " m/s";
    if (a.wind.gust.amplitude > 0.0)
      line << " gusting ±" << 100.0 * a.wind.gust.amplitude << " % every " << a.wind.gust.period_s
           << " s";
  }
  line << ")";
  return line.str();
}

void Aerodynamics::add_forces(const Matrix3X& x, const Matrix3X& v, double time_s,
                              Matrix3X& f) const {
  const double rho = m_settings.air_density_kg_m3, cd = m_settings.drag_coefficient;
  for (const auto& q : m_quads) {
    const Vec3 x0 = x.row(q[0]).transpose(), x1 = x.row(q[1]).transpose(),
               x2 = x.row(q[2]).transpose(), x3 = x.row(q[3]).transpose();
    const Vec3 v_mean = 0.25 * (v.row(q[0]) + v.row(q[1]) + v.row(q[2]) + v.row(q[3])).transpose();
    const Vec3 wind = m_settings.wind.at(0.25 * (x0 + x1 + x2 + x3), time_s);
    const Eigen::RowVector3d share =
        0.25 *
        panel_drag_force(quad_area_vector(x0, x1, x2, x3), v_mean - wind, rho, cd).transpose();
    for (Index k : q) f.row(k) += share;
  }
  // A triangle panel: vector area ½ (x1 − x0) × (x2 − x0), shared by its three corners.
  for (const auto& t : m_triangles) {
    const Vec3 x0 = x.row(t[0]).transpose(), x1 = x.row(t[1]).transpose(),
               x2 = x.row(t[2]).transpose();
    const Vec3 v_mean = (v.row(t[0]) + v.row(t[1]) + v.row(t[2])).transpose() / 3.0;
    const Vec3 wind = m_settings.wind.at((x0 + x1 + x2) / 3.0, time_s);
    const Eigen::RowVector3d share =
        panel_drag_force(0.5 * (x1 - x0).cross(x2 - x0), v_mean - wind, rho, cd).transpose() / 3.0;
    for (Index k : t) f.row(k) += share;
  }
}

}  // namespace weft::sim
