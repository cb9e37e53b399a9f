#include "sim/simulator.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sim/constraints/carried_tension.h"
#include "sim/integrators/implicit_euler.h"

namespace weft::sim {
namespace {

std::string divergence_message(long step, double time_s, const std::string& quantity) {
  std::ostringstream out;
  out << "simulation diverged at step " << step << " (t = " << time_s << " s): " << quantity;
  return out.str();
}

}  // namespace

DivergenceError::DivergenceError(long step, double time_s, std::string quantity)
    : std::runtime_error(divergence_message(step, time_s, quantity)),
      m_step(step),
      m_time_s(time_s),
      m_quantity(std::move(quantity)) {}

Simulator::Simulator(ClothMesh mesh, const Material& material, std::vector<Index> pinned,
                     const SimSettings& settings)
    : m_mesh(std::move(mesh)),
      m_settings(settings),
      m_model(settings.model == ClothModel::mass_spring
                  ? MassSpringModel(m_mesh, material,
                                    settings.projection.method == ProjectionMethod::none)
                  : MassSpringModel()),
      m_terms(make_force_terms(m_mesh, material, settings.model,
                               settings.projection.method == ProjectionMethod::none)),
      m_pinned(std::move(pinned)) {
  const Index n = m_mesh.vertex_count();
  m_mass_kg = material.density_kg_m2 * m_mesh.vertex_area_m2;
  m_inv_mass = m_mass_kg.cwiseInverse();
  for (Index p : m_pinned) m_inv_mass[p] = 0.0;
  // Unused vertices (outside a trimmed specimen) have no mass and never move, like a pin.
  for (Index v = 0; v < n; ++v)
    if (!m_mesh.is_used(v)) m_inv_mass[v] = 0.0;
  m_warp_weft_edges = make_edge_constraints(m_mesh, ConstrainedEdges::warp_weft,
                                            Eigen::VectorXd::Ones(n));  // all of them
  m_projector = make_projector(m_mesh, m_inv_mass, settings.projection, settings.sparse_backend);
  if (settings.aero.enabled) m_aero = std::make_unique<Aerodynamics>(m_mesh.quads, settings.aero);
  m_posed_obstacles = posed_obstacles(settings.obstacles, settings.obstacle_motions, 0.0);
  if (settings.self_collision.enabled)
    m_self = std::make_unique<SelfCollision>(m_mesh, settings.self_collision);
  ExplicitSystem relaxation_system;  // dynamic_relaxation's, made below
  if (settings.integrator == Integrator::implicit_euler) {
    std::vector<EdgeConstraint> tension_edges;
    if (carries_tension()) tension_edges = m_projector->constraints();
    ImplicitSolveSettings solve;
    solve.method = settings.implicit_solve;
    solve.backend = settings.sparse_backend;
    solve.cg_tolerance = settings.implicit_cg_tolerance;
    m_implicit = std::make_unique<ImplicitEuler>(m_model, m_mass_kg, m_inv_mass, solve,
                                                 std::move(tension_edges), m_terms);
  } else {  // explicit, or dynamic relaxation (made below: it needs the stiffness bound)
    ExplicitSystem system;
    system.internal_forces = [this](const Matrix3X& x, Matrix3X& f) {
      m_timers.time(Phase::forces, [&] { add_internal_forces(x, f); });
    };
    if (m_aero) {
      system.velocity_forces = [this](const Matrix3X& x, const Matrix3X& v, Matrix3X& f) {
        m_timers.time(Phase::forces, [&] { m_aero->add_forces(x, v, m_state.time_s, f); });
      };
    }
    system.mass_kg = m_mass_kg;
    system.inv_mass = m_inv_mass;
    system.gravity_m_s2 = settings.gravity_m_s2;
    system.damping_1_s = settings.air_damping_1_s;
    if (settings.integrator != Integrator::dynamic_relaxation)
      m_explicit = std::make_unique<ExplicitStepper>(settings.integrator, std::move(system));
    else
      relaxation_system = std::move(system);
  }
  m_state.x = m_mesh.rest_positions;
  m_state.v = Matrix3X::Zero(n, 3);
  m_initial_x = m_state.x;

  // Symplectic Euler, velocity Verlet and central difference are stable for h < 2/ω_max (RK4
  // for h < 2√2/ω_max, explicit Euler never without damping); ω_max² ≤ max_i bound_i / m_i
  // (Gershgorin).
  Eigen::VectorXd bound = m_model.stiffness_row_bound(n);
  for (const auto& term : m_terms) term->add_stiffness_row_bound(bound);
  double omega2 = 0.0;
  for (Index i = 0; i < n; ++i)
    if (m_inv_mass[i] > 0.0) omega2 = std::max(omega2, bound[i] * m_inv_mass[i]);
  m_critical_step_s = omega2 > 0.0 ? 2.0 / std::sqrt(omega2) : 1.0;
  const double automatic = settings.integrator == Integrator::implicit_euler
                               ? settings.implicit_default_step_s
                               : settings.time_step_safety * m_critical_step_s;
  m_time_step_s = settings.time_step_s.value_or(automatic);
  // Dynamic relaxation: one iteration per step of the explicit integrators' step, with
  // fictitious masses stable at it (sim/integrators/dynamic_relaxation.h).
  if (settings.integrator == Integrator::dynamic_relaxation)
    m_relaxation = std::make_unique<DynamicRelaxation>(std::move(relaxation_system), bound,
                                                       m_time_step_s);
}

Simulator::~Simulator() = default;

void Simulator::advance(double dt_s) {
  if (dt_s <= 0.0) return;
  const long substeps = static_cast<long>(std::ceil(dt_s / m_time_step_s - 1e-9));
  const double h = dt_s / static_cast<double>(substeps);
  const double t_end = m_state.time_s + dt_s;
  for (long s = 0; s < substeps; ++s) step(h);
  m_state.time_s = t_end;  // no drift from summing substeps
}

void Simulator::set_initial_positions(const Matrix3X& x) {
  if (m_steps > 0)
    throw std::invalid_argument("initial positions can only be set before the first step");
  if (x.rows() != m_state.x.rows())
    throw std::invalid_argument("initial positions: expected " + std::to_string(m_state.x.rows()) +
                                " vertices, got " + std::to_string(x.rows()));
  for (Index i = 0; i < x.rows(); ++i)
    if (!x.row(i).allFinite())
      throw std::invalid_argument("initial positions: vertex " + std::to_string(i) +
                                  " has a non-finite position");
  m_state.x = x;
  m_state.v.setZero();
  m_initial_x = x;
}

void Simulator::set_pin_path(const std::vector<Index>& vertices, const PinPath& path) {
  for (Index v : vertices) {
    if (std::find(m_pinned.begin(), m_pinned.end(), v) == m_pinned.end())
      throw std::invalid_argument("vertex " + std::to_string(v) + " is not pinned: only pins move");
  }
  if (!path.moves()) return;
  m_pin_paths.push_back(path);
  for (Index v : vertices) m_moving_pins.push_back({v, m_pin_paths.size() - 1});
}

// Every integrator leaves a pinned vertex's velocity as it is (zero acceleration), so the
// velocity that reaches the path's position at t + h carries it there; it is then set exactly.
void Simulator::move_pins(double h_s) {
  for (const MovingPin& p : m_moving_pins)
    m_state.v.row(p.vertex) = (pin_position(p, m_state.time_s + h_s) - m_state.x.row(p.vertex)) / h_s;
}

Eigen::RowVector3d Simulator::pin_position(const MovingPin& pin, double time_s) const {
  return m_initial_x.row(pin.vertex) + m_pin_paths[pin.path].offset_at(time_s).transpose();
}

// Fast projection's multipliers give the constraint force to carry (carried_tension.h);
// pairwise projection has none.
bool Simulator::carries_tension() const {
  return m_projector && m_settings.projection.carry_tension &&
         m_settings.projection.method == ProjectionMethod::fast_projection;
}

void Simulator::step(double h_s) {
  m_x_start = m_state.x;
  move_pins(h_s);
  integrate(h_s);
  for (const MovingPin& p : m_moving_pins)
    m_state.x.row(p.vertex) = pin_position(p, m_state.time_s + h_s);  // exactly, not x + h v
  pose_obstacles(m_state.time_s, m_state.time_s + h_s);
  // With a projection, push-out and projection alternate (block Gauss–Seidel over contacts and
  // constraints), ending with a projection so that the step meets the tolerance; vertices may
  // end up to the residual of the last push-out inside the collision thickness. A single
  // push-out after the projection undid it where the cloth lies on an obstacle (measured on
  // the inextensible sphere drape: 30 % strain). Friction acts in the first push-out only:
  // later ones would drag contact vertices back toward their start positions.
  bool collided = m_timers.time(Phase::collide, [&] { return collide(true); });
  bool projected = false;
  if (m_projector) {
    ProjectionResult total;
    for (int round = 0; round <= kContactRounds; ++round) {
      const ProjectionResult r = m_timers.time(Phase::project, [&] { return project(h_s); });
      total.iterations += r.iterations;
      total.solve_s += r.solve_s;
      total.converged = r.converged;
      total.max_strain = r.max_strain;
      if (round == kContactRounds || !m_timers.time(Phase::collide, [&] { return collide(false); }))
        break;
      collided = true;
    }
    record_projection(total);
    projected = true;
  }
  // Velocity filter (seed 000): the velocity that carries x_n to the corrected x_{n+1}.
  if (projected || collided) m_state.v = (m_state.x - m_x_start) / h_s;
  if (m_relaxation && m_relaxation->status().reset) m_state.v.setZero();  // kinetic damping
  m_state.time_s += h_s;
  ++m_steps;
  ++m_stats.steps;
  m_timers.time(Phase::check, [&] { check_finite(); });
}

// Internal forces; gravity and mass-proportional air damping (seed 002 eq. 27: f = −α M v)
// are added by the explicit stepper.
void Simulator::add_internal_forces(const Matrix3X& x, Matrix3X& f) const {
  m_model.add_forces(x, f);
  for (const auto& term : m_terms) term->add_forces(x, f);
  if (carries_tension()) add_tension_forces(m_projector->constraints(), m_tension_k, x, f);
}

// The unconstrained step. Explicit integrators (sim/integrators/explicit_steppers.h) advance x
// and v with forces evaluated through add_internal_forces, timed as the "forces" phase (their
// vector updates are not timed: a few per cent of a step). Implicit Euler: v from one Newton
// step of backward Euler, then x ← x + h v. Pinned vertices keep their v (0, or the velocity
// move_pins() gave a moving pin).
void Simulator::integrate(double h_s) {
  if (m_explicit) {
    m_explicit->step(m_state.x, m_state.v, h_s);
    return;
  }
  if (m_relaxation) {
    (void)m_relaxation->step(m_state.x, m_state.v, h_s);
    return;
  }
  if (m_aero) {
    m_timers.time(Phase::forces, [&] {
      m_aero_forces.setZero(m_state.x.rows(), 3);
      m_aero->add_forces(m_state.x, m_state.v, m_state.time_s, m_aero_forces);
    });
  }
  m_timers.time(Phase::integrate, [&] {
    const ImplicitStepResult r =
        m_implicit->step(m_state.x, m_state.v, h_s, m_settings.gravity_m_s2,
                         m_settings.air_damping_1_s, m_tension_k, m_aero_forces);
    m_stats.solve_s += r.solve_s;
    if (!r.solved) ++m_stats.failed_implicit_solves;
    m_stats.cg_iterations += r.cg_iterations;
    m_state.x += h_s * m_state.v;
  });
}

ProjectionResult Simulator::project(double h_s) {
  const ProjectionResult r = m_projector->project(m_state.x);
  if (carries_tension())
    accumulate_tension(m_projector->constraints(), m_projector->multipliers(), h_s, m_tension_k);
  return r;
}

void Simulator::record_projection(const ProjectionResult& r) {
  m_stats.projection_iterations += r.iterations;
  m_stats.max_projection_iterations = std::max(m_stats.max_projection_iterations, r.iterations);
  if (!r.converged) ++m_stats.unconverged_steps;
  m_stats.worst_projected_strain = std::max(m_stats.worst_projected_strain, r.max_strain);
  m_stats.solve_s += r.solve_s;
}

// Obstacle push-out, with Coulomb friction against the displacement since the start of the
// step; then the cloth against itself, and the obstacles once more (frictionless) for the
// vertices that moved, so that no vertex is left inside an obstacle.
bool Simulator::collide(bool with_friction) {
  const std::vector<Obstacle>& obstacles = m_posed_obstacles;
  const double thickness = m_settings.collision_thickness_m;
  const auto push_out = [&](bool friction) {
    if (obstacles.empty()) return false;
    if (friction && m_settings.collision_friction > 0.0) {
      return push_out_of_obstacles(obstacles, m_obstacle_step_motions, thickness, m_inv_mass,
                                   m_x_start, m_settings.collision_friction, m_state.x) > 0;
    }
    return push_out_of_obstacles(obstacles, thickness, m_inv_mass, m_state.x) > 0;
  };
  bool moved = push_out(with_friction);
  if (m_self) {
    const long contacts = m_self->resolve(m_x_start, m_inv_mass, m_state.x).total();
    m_stats.max_self_contacts = std::max(m_stats.max_self_contacts, contacts);
    if (contacts > 0) {
      // Only the vertices self-collision moved can have been pushed into an obstacle.
      if (!obstacles.empty())
        push_out_of_obstacles(obstacles, thickness, m_inv_mass, m_self->moved_vertices(), m_state.x);
      moved = true;
    }
  }
  return moved;
}

// Moving obstacles (sim/collision/obstacle_motion.h): posed at the end of the step, and each
// one's rigid motion over it, which carries friction's start positions along.
void Simulator::pose_obstacles(double t0_s, double t1_s) {
  if (!any_moves(m_settings.obstacle_motions)) return;  // m_posed_obstacles stay as made
  m_posed_obstacles = posed_obstacles(m_settings.obstacles, m_settings.obstacle_motions, t1_s);
  m_obstacle_step_motions.clear();
  for (const ObstacleMotion& motion : m_settings.obstacle_motions)
    m_obstacle_step_motions.push_back(motion.motion_between(t0_s, t1_s));
}

void Simulator::check_finite() const {
  const double limit2 = m_settings.max_speed_m_s * m_settings.max_speed_m_s;
  for (Index i = 0; i < m_state.x.rows(); ++i) {
    const double v2 = m_state.v.row(i).squaredNorm();
    if (!std::isfinite(v2) || !m_state.x.row(i).allFinite()) {
      throw DivergenceError(m_steps, m_state.time_s,
                            "non-finite position or velocity at vertex " + std::to_string(i));
    }
    if (v2 > limit2) {
      std::ostringstream q;
      q << "speed of vertex " << i << " is " << std::sqrt(v2) << " m/s (limit "
        << m_settings.max_speed_m_s << " m/s; try a smaller time_step)";
      throw DivergenceError(m_steps, m_state.time_s, q.str());
    }
  }
}

StepStatistics Simulator::take_step_statistics() {
  StepStatistics out = m_stats;
  m_stats = StepStatistics{};
  return out;
}

Diagnostics Simulator::diagnostics() const {
  Diagnostics d;
  d.time_s = m_state.time_s;
  for (Index i = 0; i < m_state.x.rows(); ++i) {
    if (!m_mesh.is_used(i)) continue;  // massless and still
    const double v2 = m_state.v.row(i).squaredNorm();
    d.kinetic_energy_J += 0.5 * m_mass_kg[i] * v2;
    d.max_speed_m_s = std::max(d.max_speed_m_s, std::sqrt(v2));
    d.gravity_energy_J -= m_mass_kg[i] * m_state.x.row(i).dot(m_settings.gravity_m_s2.transpose());
  }
  d.elastic_energy_J = m_model.energy(m_state.x);
  for (const auto& term : m_terms) d.elastic_energy_J += term->energy(m_state.x);
  d.max_strain = max_edge_strain(m_warp_weft_edges, m_state.x);
  d.mean_strain = mean_edge_strain(m_warp_weft_edges, m_state.x);
  return d;
}

}  // namespace weft::sim
