#include "sim/integrators/dynamic_relaxation.h"

#include <cmath>
#include <string>
#include <utility>

#include "base/check.h"

namespace weft::sim {

Eigen::VectorXd fictitious_masses_kg(const Eigen::VectorXd& row_bound_N_m,
                                     const Eigen::VectorXd& mass_kg, double h_s,
                                     double mass_safety) {
  // Misuse is a bug in the caller, checked in release builds too.
  WEFT_CHECK(row_bound_N_m.size() == mass_kg.size(),
             "fictitious_masses_kg: " + std::to_string(row_bound_N_m.size()) + " row bounds but " +
                 std::to_string(mass_kg.size()) + " masses");
  WEFT_CHECK(h_s > 0.0 && std::isfinite(h_s),
             "fictitious_masses_kg: step " + std::to_string(h_s) + " s");
  WEFT_CHECK(mass_safety >= 1.0, "fictitious_masses_kg: mass safety " +
                                     std::to_string(mass_safety) + ", expected >= 1");
  Eigen::VectorXd m(mass_kg.size());
  const double scale = mass_safety * 0.25 * h_s * h_s;  // s h²/4, s²
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    WEFT_CHECK(row_bound_N_m[i] >= 0.0, "fictitious_masses_kg: row bound " +
                                            std::to_string(row_bound_N_m[i]) + " N/m at vertex " +
                                            std::to_string(i));
    m[i] = row_bound_N_m[i] > 0.0 ? scale * row_bound_N_m[i] : mass_kg[i];
  }
  return m;
}

double free_kinetic_energy_J(const Eigen::VectorXd& mass_kg, const Eigen::VectorXd& inv_mass,
                             const Matrix3X& v) {
  double energy = 0.0;
  for (Index i = 0; i < v.rows(); ++i)
    if (inv_mass[i] > 0.0) energy += 0.5 * mass_kg[i] * v.row(i).squaredNorm();
  return energy;
}

double relative_residual(const Matrix3X& residual_N, const Eigen::VectorXd& mass_kg,
                         const Eigen::VectorXd& inv_mass, const Vec3& gravity_m_s2) {
  double r2 = 0.0, load2 = 0.0;
  const double g2 = gravity_m_s2.squaredNorm();
  for (Index i = 0; i < residual_N.rows(); ++i) {
    if (!(inv_mass[i] > 0.0)) continue;
    r2 += residual_N.row(i).squaredNorm();
    load2 += mass_kg[i] * mass_kg[i] * g2;
  }
  return load2 > 0.0 ? std::sqrt(r2 / load2) : std::sqrt(r2);
}

DynamicRelaxation::DynamicRelaxation(const System& system, double h_max_s,
                                     RelaxationSettings settings)
    : m_settings(settings), m_h_max_s(h_max_s) {
  system.check();
  m_fictitious_mass_kg = fictitious_masses_kg(system.stiffness_row_bound(), system.mass_kg, h_max_s,
                                              m_settings.mass_safety);
}

StepReport DynamicRelaxation::step(const System& system, State& state, double h_s) {
  Matrix3X& x = state.x;
  Matrix3X& v = state.v;
  const Index n = system.vertex_count();
  WEFT_CHECK(x.rows() == n && v.rows() == n && m_fictitious_mass_kg.size() == n,
             "DynamicRelaxation::step: " + std::to_string(x.rows()) + " positions and " +
                 std::to_string(v.rows()) + " velocities for " + std::to_string(n) + " vertices");
  WEFT_CHECK(h_s > 0.0 && !(h_s > m_h_max_s * (1.0 + 1e-12)),
             "DynamicRelaxation::step: step " + std::to_string(h_s) + " s, expected in (0, " +
                 std::to_string(m_h_max_s) + "]");
  const Eigen::VectorXd& m = m_fictitious_mass_kg;
  const Eigen::VectorXd& inv_mass = system.inv_mass;

  // R(x_n) = f(x_n) + M g: the physical load, no damping.
  m_residual.setZero(n, 3);
  system.add_forces(x, m_residual);
  if (system.has_velocity_forces()) {  // e.g. a steady wind's load on the cloth at rest
    m_zero_velocity.setZero(n, 3);
    system.add_velocity_forces(x, m_zero_velocity, state.time_s, m_residual);
  }
  const Eigen::RowVector3d g = system.gravity_m_s2.transpose();
  for (Index i = 0; i < n; ++i) m_residual.row(i) += system.mass_kg[i] * g;
  m_status.residual = relative_residual(m_residual, system.mass_kg, inv_mass, system.gravity_m_s2);

  // Kick: v_{n+½} = v_{n−½} + h M̃⁻¹ R_n (a half kick from rest after a start or a reset).
  const double kinetic_before = free_kinetic_energy_J(m, inv_mass, v);
  m_v_previous = v;
  const double h_kick = m_restart ? 0.5 * h_s : h_s;
  for (Index i = 0; i < n; ++i)
    if (inv_mass[i] > 0.0) v.row(i) += (h_kick / m[i]) * m_residual.row(i);
  const double kinetic_after = free_kinetic_energy_J(m, inv_mass, v);

  ++m_status.iterations;
  m_status.reset = !m_restart && kinetic_after < kinetic_before;
  StepReport report;
  report.kinetic_reset = m_status.reset;
  if (m_status.reset) {
    // The kinetic energy peaked between v_{n−½} and v_{n+½}: back to x* = x_n − (h/2) v_{n−½}
    // and start again from rest.
    for (Index i = 0; i < n; ++i) {
      if (!(inv_mass[i] > 0.0)) continue;
      x.row(i) -= (0.5 * h_s) * m_v_previous.row(i);
      v.row(i).setZero();
    }
    ++m_status.kinetic_peaks;
    m_restart = true;
    m_status.kinetic_energy_J = 0.0;
    return report;
  }
  x += h_s * v;  // pins move by their own velocity (0 when fixed), as in ExplicitStepper
  m_restart = false;
  m_status.kinetic_energy_J = kinetic_after;
  return report;
}

const RelaxationStatus& DynamicRelaxation::relax(const System& system, Matrix3X& x, Matrix3X& v,
                                                 double tolerance, long max_iterations) {
  for (long k = 0; k < max_iterations; ++k) {
    step(system, x, v, m_h_max_s);
    if (m_status.residual <= tolerance) break;
  }
  return m_status;
}

void DynamicRelaxation::save_state(StateWriter& out) const {
  out.section("dynamic relaxation");
  out.pod(m_restart);
  out.pod(m_status);
}

void DynamicRelaxation::restore_state(StateReader& in) {
  in.section("dynamic relaxation");
  in.pod(m_restart);
  in.pod(m_status);
}

}  // namespace weft::sim
