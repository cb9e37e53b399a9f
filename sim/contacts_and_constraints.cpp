#include "sim/contacts_and_constraints.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/enum_names.h"
#include "sim/constraints/inextensibility.h"

namespace weft::sim {

ContactsAndConstraints::ContactsAndConstraints(const ClothMesh& mesh,
                                               const Eigen::VectorXd& inv_mass,
                                               const SimSettings& settings)
    : m_mesh(mesh), m_settings(settings), m_inv_mass(inv_mass) {
  m_projector = make_projector(mesh, inv_mass, settings.projection, settings.sparse_backend);
  // Fast projection's multipliers give the constraint force to carry (carried_tension.h);
  // pairwise projection has none.
  if (m_projector && settings.projection.carry_tension &&
      settings.projection.method == ProjectionMethod::fast_projection)
    m_tension = std::make_shared<CarriedTensionTerm>(m_projector->constraints());
  m_posed_obstacles = posed_obstacles(settings.obstacles, settings.obstacle_motions, 0.0);
  if (settings.self_collision.enabled)
    m_self = std::make_unique<SelfCollision>(mesh, settings.self_collision);
  if (m_self && settings.self_collision.impact_zones)
    m_zones = std::make_unique<ImpactZones>(mesh,
                                            impact_zone_fraction * m_self->thickness_m());
}

ContactsAndConstraints::~ContactsAndConstraints() = default;

void ContactsAndConstraints::pose_obstacles(double t0_s, double t1_s) {
  if (!any_moves(m_settings.obstacle_motions)) return;  // m_posed_obstacles stay as made
  m_posed_obstacles = posed_obstacles(m_settings.obstacles, m_settings.obstacle_motions, t1_s);
  m_obstacle_step_motions.clear();
  for (const ObstacleMotion& motion : m_settings.obstacle_motions)
    m_obstacle_step_motions.push_back(motion.motion_between(t0_s, t1_s));
}

bool ContactsAndConstraints::resolve(const Matrix3X& x_start, Matrix3X& x, double h_s,
                                     PhaseTimers& timers, StepStatistics& stats,
                                     const Matrix3X* failsafe_from) {
  bool collided = timers.time(Phase::collide, [&] { return collide(x_start, x, true, stats); });
  if (!m_projector) {
    if (m_zones && failsafe_from) {
      timers.time(Phase::collide, [&] { failsafe(*failsafe_from, x, stats); });
      collided = collided || !m_zones->zone_vertices().empty();  // a zone moved x
    }
    return collided;
  }
  ProjectionResult total;
  for (int round = 0; round <= kContactRounds; ++round) {
    const ProjectionResult r = timers.time(Phase::project, [&] { return project(x, h_s); });
    total.iterations += r.iterations;
    total.solve_s += r.solve_s;
    total.factorizations += r.factorizations;
    total.reuse_iterations += r.reuse_iterations;
    total.converged = r.converged;
    total.max_strain = r.max_strain;
    if (round == kContactRounds ||
        !timers.time(Phase::collide, [&] { return collide(x_start, x, false, stats); }))
      break;
  }
  if (m_zones && failsafe_from) {
    timers.time(Phase::collide, [&] { failsafe(*failsafe_from, x, stats); });
    // The zones' rigid motions stretch the edges that leave a zone, which the projections with
    // the zones held may not bring back: a step left beyond the tolerance missed it (counted,
    // and warned of at the end of a run), as a projection that missed it would have.
    if (!m_zones->zone_vertices().empty() &&
        m_settings.projection.method == ProjectionMethod::fast_projection) {
      total.max_strain = max_edge_strain(m_projector->constraints(), x);
      total.converged = total.converged && total.max_strain <= m_settings.projection.tolerance;
    }
  }
  record(total, stats);
  return true;
}

void ContactsAndConstraints::resting_contacts(const Matrix3X& x,
                                              std::vector<ObstacleContact>& out) const {
  out.clear();
  const std::vector<Obstacle>& obstacles = m_posed_obstacles;
  if (obstacles.empty() || any_moves(m_settings.obstacle_motions)) return;
  const double reach_m = resting_reach * m_settings.collision_thickness_m;
  for (Index i = 0; i < x.rows(); ++i) {
    if (!(m_inv_mass[i] > 0.0)) continue;
    const Vec3 p = x.row(i).transpose();
    const Obstacle& nearest = obstacles[nearest_obstacle(obstacles, p)];
    if (signed_distance(nearest, p) <= reach_m) out.push_back({i, outward_normal(nearest, p)});
  }
}

ProjectionResult ContactsAndConstraints::project(Matrix3X& x, double h_s) {
  const ProjectionResult r = m_projector->project(x);
  if (m_tension) m_tension->accumulate(m_projector->multipliers(), h_s);
  return r;
}

void ContactsAndConstraints::record(const ProjectionResult& r, StepStatistics& stats) {
  stats.projection_iterations += r.iterations;
  stats.projection_factorizations += r.factorizations;
  stats.projection_reuse_iterations += r.reuse_iterations;
  stats.max_projection_iterations = std::max(stats.max_projection_iterations, r.iterations);
  if (!r.converged) ++stats.unconverged_steps;
  stats.worst_projected_strain = std::max(stats.worst_projected_strain, r.max_strain);
  stats.solve_s += r.solve_s;
}

// The impact zones leave the edges from a zone to the rest of the cloth stretched. With a
// projection, the cloth is projected once more with every zone vertex so far held (inverse
// mass 0: a zone keeps its rigid motion) and the zones are sought again over the new motion,
// up to kHeldRounds times; the impact zones always come last, so no crossing is left. The
// projector of these projections is made once and given the held vertices at each round
// (set_inverse_masses: fast projection keeps its analysis); it starts each step afresh, so
// nothing of it carries from one step to the next. If the last round's zones moved again,
// the edges they stretched are taken into them (absorb_stretched) without a projection.
void ContactsAndConstraints::failsafe(const Matrix3X& x_start, Matrix3X& x, StepStatistics& stats) {
  ImpactZoneCounts counts = m_zones->resolve(x_start, m_inv_mass, x);
  long most = counts.zone_vertices;
  if (m_projector && counts.zone_vertices > 0) {
    for (int round = 0; round < kHeldRounds && (round == 0 || counts.collisions > 0); ++round) {
      const Eigen::VectorXd held = zones_held();
      if (!m_held_projector) {
        ProjectionSettings held_settings = m_settings.projection;
        held_settings.stall_fraction = kHeldStallFraction;
        m_held_projector =
            make_projector(m_mesh, m_inv_mass, held_settings, m_settings.sparse_backend);
      }
      m_held_projector->set_inverse_masses(held, /*fresh=*/round == 0);
      const ProjectionResult r = m_held_projector->project(x);
      stats.projection_iterations += r.iterations;  // its convergence shows in the frame's strain
      stats.projection_factorizations += r.factorizations;
      stats.projection_reuse_iterations += r.reuse_iterations;
      stats.solve_s += r.solve_s;
      // The zones take in the free ends of the edges left stretched beyond the tolerance: a
      // zone that moves rigidly with them keeps those edges at their start length. Those are
      // the edges leaving a zone, and where the projection stalled (two zones pulling the
      // free cloth between them apart), also edges between free vertices.
      const std::vector<std::array<Index, 2>> stretched = stretched_edges(held, x);
      m_zones->absorb(stretched);
      counts = m_zones->resolve(x_start, m_inv_mass, x, /*grow=*/true);
      if (!stretched.empty()) counts.collisions += static_cast<long>(stretched.size());
      most = std::max(most, counts.zone_vertices);
    }
    if (counts.collisions > 0) counts = absorb_stretched(x_start, x, counts);
    most = std::max(most, counts.zone_vertices);
  }
  stats.max_impact_zone_vertices = std::max(stats.max_impact_zone_vertices, most);
  if (!counts.resolved) ++stats.unresolved_impact_steps;
}

Eigen::VectorXd ContactsAndConstraints::zones_held() const {
  Eigen::VectorXd held = m_inv_mass;
  for (const Index v : m_zones->zone_vertices()) held[v] = 0.0;
  return held;
}

std::vector<std::array<Index, 2>> ContactsAndConstraints::stretched_edges(
    const Eigen::VectorXd& held, const Matrix3X& x) const {
  std::vector<std::array<Index, 2>> stretched;
  if (m_settings.projection.method != ProjectionMethod::fast_projection) return stretched;
  for (const EdgeConstraint& c : m_projector->constraints())
    if ((held[c.a] != 0.0 || held[c.b] != 0.0) &&
        std::abs(edge_strain(x.row(c.a), x.row(c.b), c.rest_m)) > m_settings.projection.tolerance)
      stretched.push_back({c.a, c.b});
  return stretched;
}

// The held rounds ran out with zones that moved again after the last projection. Each edge
// they left beyond the tolerance joins its zone, which moves rigidly anew, until none is left
// or the zones stop growing (an edge to a pin, which keeps its own motion). The zones can only
// grow, and a zone that took in a whole piece of cloth moves it rigidly from its start: its
// edges keep their start lengths and it crosses nothing.
ImpactZoneCounts ContactsAndConstraints::absorb_stretched(const Matrix3X& x_start, Matrix3X& x,
                                                          ImpactZoneCounts counts) {
  for (;;) {
    const std::vector<std::array<Index, 2>> stretched = stretched_edges(zones_held(), x);
    if (stretched.empty()) return counts;
    const long before = counts.zone_vertices;
    m_zones->absorb(stretched);
    counts = m_zones->resolve(x_start, m_inv_mass, x, /*grow=*/true);
    if (counts.zone_vertices <= before) return counts;
  }
}

// Obstacle push-out, with Coulomb friction against the displacement since the start of the
// step; then the cloth against itself, and the obstacles once more (frictionless) for the
// vertices that moved, so that no vertex is left inside an obstacle.
bool ContactsAndConstraints::collide(const Matrix3X& x_start, Matrix3X& x, bool with_friction,
                                     StepStatistics& stats) {
  const std::vector<Obstacle>& obstacles = m_posed_obstacles;
  const double thickness = m_settings.collision_thickness_m;
  const auto push_out = [&](bool friction) {
    if (obstacles.empty()) return false;
    if (friction && m_settings.collision_friction > 0.0) {
      return push_out_of_obstacles(obstacles, m_obstacle_step_motions, thickness, m_inv_mass,
                                   x_start, m_settings.collision_friction, x) > 0;
    }
    return push_out_of_obstacles(obstacles, thickness, m_inv_mass, x) > 0;
  };
  bool moved = push_out(with_friction);
  if (m_self) {
    const long contacts = m_self->resolve(x_start, m_inv_mass, x).total();
    stats.max_self_contacts = std::max(stats.max_self_contacts, contacts);
    if (contacts > 0) {
      // Only the vertices self-collision moved can have been pushed into an obstacle.
      if (!obstacles.empty())
        push_out_of_obstacles(obstacles, thickness, m_inv_mass, m_self->moved_vertices(), x);
      moved = true;
    }
  }
  return moved;
}

std::string ContactsAndConstraints::explain_project() const {
  std::ostringstream line;
  if (!m_projector) return "project: off (no constraints)";
  const ProjectionSettings& p = m_settings.projection;
  line << "project: " << base::enum_name(projection_method_names, p.method) << " on "
       << m_projector->constraints().size()
       << (p.edges == ConstrainedEdges::warp_weft ? " warp/weft" : " triangle") << " edges, ";
  if (p.method == ProjectionMethod::fast_projection)
    line << "tolerance " << p.tolerance << ", at most " << p.max_iterations << " iterations";
  else
    line << p.max_iterations << " sweeps, max stretch " << p.max_stretch;
  return line.str();
}

std::string ContactsAndConstraints::explain_collide() const {
  std::ostringstream line;
  if (m_settings.obstacles.empty()) {
    line << "collide: " << (m_self ? "no obstacles" : "off (no obstacles, no self-collision)");
  } else {
    std::size_t meshes = 0, moving = 0;
    for (const Obstacle& o : m_settings.obstacles) meshes += std::holds_alternative<MeshObstacle>(o);
    for (const ObstacleMotion& m : m_settings.obstacle_motions) moving += m.moves();
    line << "collide: " << m_settings.obstacles.size() << " obstacles (" << meshes << " meshes, "
         << moving << " moving), thickness " << 1e3 * m_settings.collision_thickness_m
         << " mm, friction " << m_settings.collision_friction;
    if (m_settings.resting_contacts && m_settings.integrator == Integrator::implicit_euler)
      line << ", resting contacts held in the solve";
  }
  if (m_self) {
    line << "; self-collision over " << m_self->triangle_count() << " triangles and "
         << m_self->edge_count() << " edges, thickness " << 1e3 * m_self->thickness_m()
         << " mm, marbles of radius " << 1e3 * m_self->marble_radius_m()
         << " mm, candidate margin " << 1e3 * m_self->margin_m() << " mm";
    const double interval_s = m_settings.self_collision.failsafe_interval_s;
    if (!m_zones)
      line << ", no impact zones";
    else if (interval_s > 0.0)
      line << ", impact zones over windows of at most " << 1e3 * interval_s << " ms";
    else
      line << ", impact zones every step";
  }
  return line.str();
}

void ContactsAndConstraints::save_state(StateWriter& out) const {
  out.section("contacts and constraints");
  out.pod(m_projector != nullptr);
  if (m_projector) m_projector->save_state(out);
  out.pod(m_tension != nullptr);
  if (m_tension) out.matrix(m_tension->tension_N_m());
  out.pod(m_self != nullptr);
  if (m_self) m_self->save_state(out);
}

void ContactsAndConstraints::restore_state(StateReader& in) {
  in.section("contacts and constraints");
  if (in.pod<bool>() != (m_projector != nullptr)) in.fail("another projection setting");
  if (m_projector) m_projector->restore_state(in);
  if (in.pod<bool>() != (m_tension != nullptr)) in.fail("another carried-tension setting");
  if (m_tension) {
    Eigen::VectorXd k;
    in.matrix(k);
    try {
      m_tension->restore_tension(k);
    } catch (const std::invalid_argument& e) {
      in.fail(e.what());
    }
  }
  if (in.pod<bool>() != (m_self != nullptr)) in.fail("another self-collision setting");
  if (m_self) m_self->restore_state(in);
}

}  // namespace weft::sim
