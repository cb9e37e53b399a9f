// Simulator::explain(): which terms and phases a scene's simulation actually runs.
#include <algorithm>
#include <sstream>

#include "sim/simulator.h"

namespace weft::sim {

std::vector<std::string> Simulator::explain() const {
  std::ostringstream pins;
  pins << "pins: " << m_pinned.size() - m_moving_pins.size() << " fixed, " << m_moving_pins.size()
       << " moving vertices";
  if (m_taut.chains > 0)
    pins << "; " << m_taut.vertices.size() << " vertices held on " << m_taut.chains
         << (m_taut.chains == 1 ? " chain" : " chains")
         << " pulled straight between still pins at its rest length (inextensible: no other shape)";
  std::vector<std::string> lines{explain_integrate(), explain_forces(),
                                 m_contacts->explain_project(), m_contacts->explain_collide(),
                                 pins.str()};
  if (m_settings.remesh.enabled) {
    const RemeshSettings& r = m_settings.remesh;
    std::ostringstream remesh;
    remesh << "remesh: ";
    if (r.indicator > 0.0)
      remesh << "when max |curvature| h^2 > " << r.indicator << " c, checked every "
             << r.every_steps << (r.every_steps == 1 ? " step" : " steps")
             << (r.coarsen > 0.0 ? ", or when the mesh grew " : "");
    if (r.indicator > 0.0 && r.coarsen > 0.0)
      remesh << r.coarsen << "x finer than the curvature asks (coarsening)";
    if (r.indicator <= 0.0)
      remesh << "every " << r.every_steps << " steps";
    remesh << ", h = clamp(sqrt(c / |curvature|), " << 1e3 * r.h_min_m << " mm, "
           << 1e3 * r.h_max_m << " mm), c = " << 1e3 * r.c_m
           << " mm (CGAL Delaunay refinement, boundary and pins kept; positions transferred "
           << (r.transfer == remesh::PositionTransfer::quadratic ? "quadratically" : "linearly")
           << "); now "
           << m_mesh.vertex_count() << " vertices, " << m_mesh.faces.size() << " triangles";
    lines.push_back(remesh.str());
  }
  return lines;
}

std::string Simulator::explain_integrate() const {
  std::ostringstream line;
  line << "integrate: " << integrator_name(m_settings.integrator);
  if (m_adaptive)
    line << ", adaptive h from " << 1e3 * m_adaptive->settings().min_step_s << " to "
         << 1e3 * m_adaptive->settings().max_step_s
         << " ms (following the projection's iterations)";
  else
    line << ", h = " << 1e3 * m_time_step_s << " ms";
  if (m_settings.integrator == Integrator::implicit_euler) {
    if (m_settings.implicit_solve == ImplicitSolve::direct)
      line << ", sparse direct solve (" << sparse_backend_name(m_settings.sparse_backend) << ")";
    else
      line << ", conjugate gradients to " << m_settings.implicit_cg_tolerance << " ("
           << base::enum_name(cg_preconditioner_names, m_settings.implicit_cg_preconditioner)
           << ": " << preconditioner_in_use(m_integrator_settings.implicit_solve) << ")";
    const bool explicit_stiffness =
        std::any_of(m_system.terms.begin(), m_system.terms.end(), [](const auto& term) {
          return term->has_stiffness() && !term->stiffness_in_time_step();
        });
    if (explicit_stiffness)
      line << ", bending explicit (stable at h ≤ " << 1e3 * m_explicit_stable_step_s << " ms)";
  }
  if (const DynamicRelaxation* relaxation = this->relaxation()) {
    const Eigen::ArrayXd ratio =
        relaxation->fictitious_mass_kg().array() / m_system.mass_kg.array();
    line << " of pseudo-time per iteration (frames show iterations, not motion), fictitious "
            "masses "
         << ratio.minCoeff() << "–" << ratio.maxCoeff()
         << " × physical, kinetic damping (air damping unused)";
  }
  return line.str();
}

// Every force term of the System, as it describes itself.
std::string Simulator::explain_forces() const {
  std::ostringstream line;
  line << "forces (" << cloth_model_name(m_settings.model) << "): gravity, air damping "
       << m_settings.air_damping_1_s << " 1/s";
  for (const auto& term : m_system.terms) line << ", " << term->describe();
  for (const auto& term : m_system.velocity_terms) line << ", " << term->describe();
  return line.str();
}

}  // namespace weft::sim
