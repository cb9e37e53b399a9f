// Simulator::explain(): which terms and phases a scene's simulation actually runs.
#include <sstream>

#include "sim/simulator.h"

namespace weft::sim {
namespace {

const char* projection_name(ProjectionMethod method) {
  switch (method) {
    case ProjectionMethod::none:
      return "none";
    case ProjectionMethod::fast_projection:
      return "fast_projection";
    case ProjectionMethod::pairwise:
      return "pairwise";
  }
  return "?";
}

}  // namespace

std::vector<std::string> Simulator::explain() const {
  std::vector<std::string> lines;
  std::ostringstream line;
  const auto emit = [&] {
    lines.push_back(line.str());
    line.str("");
  };

  line << "integrate: " << integrator_name(m_settings.integrator) << ", h = " << 1e3 * m_time_step_s
       << " ms";
  if (m_implicit) {
    if (m_settings.implicit_solve == ImplicitSolve::direct)
      line << ", sparse direct solve (" << sparse_backend_name(m_settings.sparse_backend) << ")";
    else
      line << ", conjugate gradients to " << m_settings.implicit_cg_tolerance;
  }
  if (m_relaxation) {
    const Eigen::ArrayXd ratio = m_relaxation->fictitious_mass_kg().array() / m_mass_kg.array();
    line << " of pseudo-time per iteration (frames show iterations, not motion), fictitious "
            "masses "
         << ratio.minCoeff() << "–" << ratio.maxCoeff()
         << " × physical, kinetic damping (air damping unused)";
  }
  emit();

  line << "forces (" << cloth_model_name(m_settings.model) << "): gravity, air damping "
       << m_settings.air_damping_1_s << " 1/s";
  if (m_settings.model == ClothModel::mass_spring) {
    long warp_weft = 0, shear = 0;
    for (const Spring& s : m_model.springs())
      (s.kind == SpringKind::shear ? shear : warp_weft) += 1;
    if (warp_weft > 0) line << ", " << warp_weft << " warp/weft springs";
    if (shear > 0) line << ", " << shear << " shear springs";
    if (!m_model.bends().empty()) line << ", " << m_model.bends().size() << " bending stencils";
  }
  for (const auto& term : m_terms) line << ", " << term->describe();
  if (m_aero) {
    const AeroSettings& a = m_aero->settings();
    line << ", air drag on " << m_aero->panel_count() << " quads (C_d " << a.drag_coefficient
         << ", " << a.air_density_kg_m3 << " kg/m³";
    if (a.wind.velocity_m_s.norm() > 0.0) {
      line << ", wind " << a.wind.velocity_m_s.norm() << " m/s";
      if (a.wind.gust.amplitude > 0.0)
        line << " gusting ±" << 100.0 * a.wind.gust.amplitude << " % every " << a.wind.gust.period_s << " s";
    }
    line << ")";
  }
  if (carries_tension())
    line << ", carried constraint tension on " << m_projector->constraints().size() << " edges";
  emit();

  if (m_projector) {
    const ProjectionSettings& p = m_settings.projection;
    line << "project: " << projection_name(p.method) << " on " << m_projector->constraints().size()
         << (p.edges == ConstrainedEdges::warp_weft ? " warp/weft" : " triangle") << " edges, ";
    if (p.method == ProjectionMethod::fast_projection)
      line << "tolerance " << p.tolerance << ", at most " << p.max_iterations << " iterations";
    else
      line << p.max_iterations << " sweeps, max stretch " << p.max_stretch;
  } else {
    line << "project: off (no constraints)";
  }
  emit();

  if (m_settings.obstacles.empty()) {
    line << "collide: " << (m_self ? "no obstacles" : "off (no obstacles, no self-collision)");
  } else {
    std::size_t meshes = 0, moving = 0;
    for (const Obstacle& o : m_settings.obstacles) meshes += std::holds_alternative<MeshObstacle>(o);
    for (const ObstacleMotion& m : m_settings.obstacle_motions) moving += m.moves();
    line << "collide: " << m_settings.obstacles.size() << " obstacles (" << meshes << " meshes, "
         << moving << " moving), thickness " << 1e3 * m_settings.collision_thickness_m
         << " mm, friction " << m_settings.collision_friction;
  }
  if (m_self) {
    line << "; self-collision over " << m_self->triangle_count() << " triangles and "
         << m_self->edge_count() << " edges, thickness " << 1e3 * m_self->thickness_m()
         << " mm, marbles of radius " << 1e3 * m_self->marble_radius_m()
         << " mm, candidate margin " << 1e3 * m_self->margin_m() << " mm";
  }
  emit();

  line << "pins: " << m_pinned.size() - m_moving_pins.size() << " fixed, " << m_moving_pins.size()
       << " moving vertices";
  emit();
  return lines;
}

}  // namespace weft::sim
