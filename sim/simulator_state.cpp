// Simulator::save_state / restore_state (see simulator.h): the state between two steps.
// What is not saved is made anew from the scene (mesh, masses, force terms, pin paths, the
// time step) or is recomputed before it is used in every step (the start-of-step positions,
// the obstacles' poses and motions over the step) or is wall time (the phase timers).

#include "sim/simulator.h"

#include <stdexcept>
#include <string>

namespace weft::sim {

void Simulator::save_state(StateWriter& out) const {
  if (m_remeshes > 0)
    throw std::logic_error("the simulation has been remeshed " + std::to_string(m_remeshes) +
                           " times: its mesh is no longer the scene's, and a state of a "
                           "remeshed cloth cannot be saved (docs/remeshing.md)");
  out.section("simulator");
  out.pod(m_steps);
  out.pod(m_state.time_s);
  out.matrix(m_state.x);
  out.matrix(m_state.v);
  out.matrix(m_initial_x);
  out.pod(m_energy_guard_started);
  out.pod(m_start_energy_J.has_value());
  out.pod(m_start_energy_J.value_or(0.0));
  out.pod(m_energy_margin_J);
  out.pod(m_stats);
  out.pod(m_adaptive ? m_adaptive->planned_step_s() : 0.0);
  m_integrator->save_state(out);
  m_contacts->save_state(out);
  out.section("simulator end");
}

void Simulator::restore_state(StateReader& in) {
  in.section("simulator");
  const Eigen::Index n = m_state.x.rows();
  in.pod(m_steps);
  in.pod(m_state.time_s);
  in.matrix(m_state.x, n, 3);
  in.matrix(m_state.v, n, 3);
  in.matrix(m_initial_x, n, 3);
  in.pod(m_energy_guard_started);
  const bool has_start_energy = in.pod<bool>();
  const double start_energy_J = in.pod<double>();
  m_start_energy_J = has_start_energy ? std::optional<double>(start_energy_J) : std::nullopt;
  in.pod(m_energy_margin_J);
  in.pod(m_stats);
  const double planned_step_s = in.pod<double>();
  if (m_adaptive) m_adaptive->set_planned_step_s(planned_step_s);
  m_integrator->restore_state(in);
  m_contacts->restore_state(in);
  in.section("simulator end");
}

}  // namespace weft::sim
