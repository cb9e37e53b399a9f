// Simulator::save_state / restore_state (see simulator.h): the state between two steps.
// What is not saved is made anew from the scene (the mesh until the first remesh, masses,
// force terms, pin paths, the time step) or is recomputed before it is used in every step (the start-of-step positions,
// the obstacles' poses and motions over the step) or is wall time (the phase timers).

#include "sim/simulator.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sim/cloth_mesh_archive.h"

namespace weft::sim {

void Simulator::save_state(StateWriter& out) const {
  // The mesh first: a remeshed cloth's is no longer the scene's (docs/checkpoints.md).
  out.section("mesh");
  out.pod(m_remeshes);
  out.pod(m_excess_reference.has_value());
  out.pod(m_excess_reference.value_or(0.0));
  if (m_remeshes > 0) {
    save_cloth_mesh(out, m_mesh);
    out.pods(m_pinned);
    std::vector<Index> moving;
    for (const MovingPin& p : m_moving_pins) moving.push_back(p.vertex);
    out.pods(moving);
  }
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
  in.section("mesh");
  const long remeshes = in.pod<long>();
  if (remeshes < 0) in.fail("a negative remesh count");
  const bool has_excess_reference = in.pod<bool>();
  const double excess_reference = in.pod<double>();
  if (remeshes > 0) {
    if (!m_settings.remesh.enabled)
      in.fail("the state is of a cloth remeshed " + std::to_string(remeshes) +
              (remeshes == 1 ? " time" : " times") + ", this simulation has no simulation.remesh");
    ClothMesh mesh = m_mesh;
    restore_cloth_mesh(in, mesh);
    std::vector<Index> pinned, moving;
    in.pods(pinned);
    in.pods(moving);
    if (pinned.size() != m_pinned.size() || moving.size() != m_moving_pins.size())
      in.fail(std::to_string(pinned.size()) + " pins (" + std::to_string(moving.size()) +
              " moving) where the simulation has " + std::to_string(m_pinned.size()) + " (" +
              std::to_string(m_moving_pins.size()) + ")");
    for (const Index v : pinned)
      if (v < 0 || v >= mesh.vertex_count()) in.fail("a pin out of the mesh's vertices");
    for (const Index v : moving)
      if (std::find(pinned.begin(), pinned.end(), v) == pinned.end())
        in.fail("a moving pin that is not pinned");
    m_mesh = std::move(mesh);
    m_pinned = std::move(pinned);
    for (std::size_t k = 0; k < moving.size(); ++k) m_moving_pins[k].vertex = moving[k];
    const Index n = m_mesh.vertex_count();
    m_state.x.resize(n, 3);
    m_state.v.resize(n, 3);
    m_initial_x.resize(n, 3);
    rebuild_for_mesh();
  } else if (m_remeshes > 0) {
    in.fail("the state is of the scene's mesh, this simulation has been remeshed");
  }
  m_remeshes = remeshes;
  m_excess_reference =
      has_excess_reference ? std::optional<double>(excess_reference) : std::nullopt;
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
