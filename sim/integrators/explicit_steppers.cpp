#include "sim/integrators/explicit_steppers.h"

#include <string>

#include "base/check.h"

namespace weft::sim {

ExplicitStepper::ExplicitStepper(Integrator method, const System& system) : m_method(method) {
  // Misuse is a bug in the caller, checked in release builds too.
  WEFT_CHECK(method != Integrator::implicit_euler,
             "ExplicitStepper: implicit_euler is not explicit (ImplicitEuler)");
  WEFT_CHECK(method != Integrator::dynamic_relaxation,
             "ExplicitStepper: dynamic_relaxation has its own stepper");
  system.check();
}

int ExplicitStepper::force_evaluations_per_step() const {
  switch (m_method) {
    case Integrator::rk4:
      return 4;
    case Integrator::velocity_verlet:
      return 2;
    default:
      return 1;
  }
}

void ExplicitStepper::total_forces(const System& system, const Matrix3X& x, const Matrix3X& v,
                                   double time_s, double damping_1_s, Matrix3X& F) {
  F.setZero(x.rows(), 3);
  system.add_forces(x, F);
  if (system.has_velocity_forces()) system.add_velocity_forces(x, v, time_s, F);
  const Eigen::RowVector3d g = system.gravity_m_s2.transpose();
  for (Index i = 0; i < F.rows(); ++i)
    F.row(i) += system.mass_kg[i] * (g - damping_1_s * v.row(i));
}

void ExplicitStepper::kick(const System& system, double h_s, const Matrix3X& F, Matrix3X& v) {
  for (Index i = 0; i < v.rows(); ++i)
    if (system.inv_mass[i] > 0.0) v.row(i) += (h_s * system.inv_mass[i]) * F.row(i);
}

StepReport ExplicitStepper::step(const System& system, State& state, double h_s) {
  Matrix3X& x = state.x;
  Matrix3X& v = state.v;
  const Index n = system.vertex_count();
  WEFT_CHECK(x.rows() == n && v.rows() == n && system.inv_mass.size() == n,
             "ExplicitStepper::step: " + std::to_string(x.rows()) + " positions and " +
                 std::to_string(v.rows()) + " velocities for " + std::to_string(n) + " vertices");
  WEFT_CHECK(h_s > 0.0, "ExplicitStepper::step: time step " + std::to_string(h_s) + " s");
  const double alpha = system.damping_1_s;
  const double t = state.time_s;
  switch (m_method) {
    case Integrator::symplectic_euler:  // the new velocity moves the positions
      total_forces(system, x, v, t, alpha, m_force);
      kick(system, h_s, m_force, v);
      x += h_s * v;
      break;
    case Integrator::explicit_euler:  // the old velocity moves the positions
      total_forces(system, x, v, t, alpha, m_force);
      x += h_s * v;
      kick(system, h_s, m_force, v);
      break;
    case Integrator::velocity_verlet:
      total_forces(system, x, v, t, alpha, m_force);
      kick(system, 0.5 * h_s, m_force, v);
      x += h_s * v;
      total_forces(system, x, v, t, alpha, m_force);  // at x_{n+1}, damping at v½
      kick(system, 0.5 * h_s, m_force, v);
      break;
    case Integrator::rk4:
      rk4_step(system, state, h_s);
      break;
    case Integrator::central_difference:
      central_difference_step(system, state, h_s);
      break;
    case Integrator::implicit_euler:
    case Integrator::dynamic_relaxation:
      WEFT_CHECK(false, std::string("ExplicitStepper: ") + integrator_name(m_method));
      break;
  }
  return {};
}

// Stage s evaluates k_s = (v_s, a(x_s, v_s)) at y_s = y_n + c_s h k_{s−1}, c = (0, ½, ½, 1), and
// y_{n+1} = y_n + h/6 (k_1 + 2 k_2 + 2 k_3 + k_4). Pinned vertices: a = 0 and v = 0 in every
// stage, so they stay put.
void ExplicitStepper::rk4_step(const System& system, State& state, double h_s) {
  static constexpr double kWeight[4] = {1.0, 2.0, 2.0, 1.0};
  static constexpr double kNextOffset[3] = {0.5, 0.5, 1.0};  // c_{s+1}
  Matrix3X& x = state.x;
  Matrix3X& v = state.v;
  m_x_stage = x;
  m_v_stage = v;
  m_dx.setZero(x.rows(), 3);
  m_dv.setZero(x.rows(), 3);
  for (int s = 0; s < 4; ++s) {
    total_forces(system, m_x_stage, m_v_stage, state.time_s, system.damping_1_s, m_force);
    for (Index i = 0; i < x.rows(); ++i) {  // m_force becomes the acceleration a(x_s, v_s)
      if (system.inv_mass[i] > 0.0) {
        m_force.row(i) *= system.inv_mass[i];
      } else {
        m_force.row(i).setZero();
      }
    }
    m_dx += kWeight[s] * m_v_stage;
    m_dv += kWeight[s] * m_force;
    if (s < 3) {
      const double c = kNextOffset[s] * h_s;
      m_x_stage = x + c * m_v_stage;  // before m_v_stage moves on: k_x of this stage is v_s
      m_v_stage = v + c * m_force;
    }
  }
  x += (h_s / 6.0) * m_dx;
  v += (h_s / 6.0) * m_dv;
}

// Seed 002 eqs. 20–22 with centred mass damping; h̄ is the mean of the previous and current
// steps (half a step at the start, from the synchronous initial velocity).
void ExplicitStepper::central_difference_step(const System& system, State& state, double h_s) {
  Matrix3X& x = state.x;
  Matrix3X& v = state.v;
  const double h_mean = 0.5 * (m_previous_h_s + h_s);
  const double half_damping = 0.5 * system.damping_1_s * h_mean;
  total_forces(system, x, v, state.time_s, 0.0, m_force);  // f(x_n) + M g: damping centred below
  for (Index i = 0; i < x.rows(); ++i) {
    if (system.inv_mass[i] > 0.0) {
      v.row(i) =
          ((1.0 - half_damping) * v.row(i) + (h_mean * system.inv_mass[i]) * m_force.row(i)) /
          (1.0 + half_damping);
    }
  }
  x += h_s * v;
  m_previous_h_s = h_s;
}

void ExplicitStepper::save_state(StateWriter& out) const {
  out.section("explicit stepper");
  out.pod(m_method);
  out.pod(m_previous_h_s);
}

void ExplicitStepper::restore_state(StateReader& in) {
  in.section("explicit stepper");
  if (in.pod<Integrator>() != m_method) in.fail("another integrator");
  in.pod(m_previous_h_s);
}

}  // namespace weft::sim
