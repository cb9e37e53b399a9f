#include "sim/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "base/check.h"
#include "sim/cloth_remesh.h"
#include "sim/constraints/inextensibility.h"
#include "sim/remesh_relaxation.h"


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

namespace {

// max_i bound_i / m_i over the free vertices: with `bound` a Gershgorin row bound of a
// stiffness, an upper bound on the largest ω² of M⁻¹K; 0 without free vertices.
double largest_omega2(const Eigen::VectorXd& bound, const Eigen::VectorXd& inv_mass) {
  double omega2 = 0.0;
  for (Eigen::Index i = 0; i < bound.size(); ++i)
    if (inv_mass[i] > 0.0) omega2 = std::max(omega2, bound[i] * inv_mass[i]);
  return omega2;
}

// The longest step at which the stiffness left out of implicit Euler's matrix (the grid's
// bending, when explicit) stays stable: 2/ω, with ω² ≤ max_i bound_i / m_i over those terms
// (Gershgorin); infinity when there are none. For bending stencils the bound is exact: it is
// the out-of-plane checkerboard mode's ω². Inside implicit Euler an explicit force steps as in
// symplectic Euler, stable for h ω < 2; the string stiffness of a tension in the matrix
// steadies it where the cloth is taut, but not at a free hem, which tension never reaches.
double explicit_stiffness_step_s(const System& system) {
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(system.vertex_count());
  for (const auto& term : system.terms)
    if (term->has_stiffness() && !term->stiffness_in_time_step()) term->add_stiffness_row_bound(bound);
  const double omega2 = largest_omega2(bound, system.inv_mass);
  return omega2 > 0.0 ? 2.0 / std::sqrt(omega2) : std::numeric_limits<double>::infinity();
}

// Whether implicit Euler should take the grid's bending into its matrix: on request, or when
// the bending left explicit would not be stable at the run's steps (with the explicit
// integrators' safety factor): with a fixed step, when the step is longer than that; with the
// adaptive step, whose steps are then kept within it (Simulator), when that would hold them
// shorter than SimSettings::kExplicitBendingShortestStep of implicit Euler's default step.
bool bending_in_time_step(const System& system, const SimSettings& settings) {
  if (settings.integrator != Integrator::implicit_euler) return false;
  if (settings.bending_in_step != BendingInStep::automatic)
    return settings.bending_in_step == BendingInStep::implicit;
  const double stable_s = settings.time_step_safety * explicit_stiffness_step_s(system);
  if (settings.time_step.is_adaptive())
    return stable_s < std::max(SimSettings::kExplicitBendingShortestStep *
                                   settings.implicit_default_step_s,
                               settings.time_step.adaptive.min_step_s);
  const double h = settings.time_step.kind == TimeStep::Kind::fixed ? settings.time_step.fixed_s
                                                                     : settings.implicit_default_step_s;
  return h > stable_s;
}

// The physical system of a mesh, material and pins under the settings: lumped masses (inverse
// mass 0 at pins and at unused vertices outside a trimmed specimen, which never move), the
// cloth model's force terms and, when enabled, air drag.
System make_system(const ClothMesh& mesh, const Material& material,
                   const std::vector<Index>& pinned, const SimSettings& settings) {
  System system;
  const Index n = mesh.vertex_count();
  system.mass_kg = material.density_kg_m2 * mesh.vertex_area_m2;
  system.inv_mass = system.mass_kg.cwiseInverse();
  for (Index p : pinned) system.inv_mass[p] = 0.0;
  for (Index v = 0; v < n; ++v)
    if (!mesh.is_used(v)) system.inv_mass[v] = 0.0;
  system.gravity_m_s2 = settings.gravity_m_s2;
  system.damping_1_s = settings.air_damping_1_s;
  // With a projection method the warp/weft stretch is left to the constraints.
  const bool with_stretch = settings.projection.method == ProjectionMethod::none;
  system.terms = make_force_terms(mesh, material, settings.model, with_stretch);
  if (bending_in_time_step(system, settings))
    system.terms = make_force_terms(mesh, material, settings.model, with_stretch, true);
  if (settings.aero.enabled)
    system.velocity_terms.push_back(std::make_shared<Aerodynamics>(mesh.quads, mesh.faces, settings.aero));
  return system;
}

// Symplectic Euler, velocity Verlet and central difference are stable for h < 2/ω_max (RK4 for
// h < 2√2/ω_max, explicit Euler never without damping); ω_max² ≤ max_i bound_i / m_i
// (Gershgorin).
double critical_step_s(const System& system) {
  const double omega2 = largest_omega2(system.stiffness_row_bound(), system.inv_mass);
  return omega2 > 0.0 ? 2.0 / std::sqrt(omega2) : 1.0;
}

}  // namespace

Simulator::Simulator(ClothMesh mesh, const Material& material, std::vector<Index> pinned,
                     const SimSettings& settings)
    : m_mesh(std::move(mesh)),
      m_material(material),
      m_settings(settings),
      m_pinned(std::move(pinned)),
      m_system(make_system(m_mesh, material, m_pinned, settings)) {
  m_system.timers = &m_timers;
  check_remesh_settings(m_mesh, settings);
  const Index n = m_mesh.vertex_count();
  m_warp_weft_edges = make_edge_constraints(m_mesh, ConstrainedEdges::warp_weft,
                                            Eigen::VectorXd::Ones(n));  // all of them
  m_state.x = m_mesh.start();
  m_state.v = Matrix3X::Zero(n, 3);
  m_initial_x = m_state.x;
  m_critical_step_s = critical_step_s(m_system);
  m_explicit_stable_step_s = settings.time_step_safety * explicit_stiffness_step_s(m_system);
  const double automatic = settings.integrator == Integrator::implicit_euler
                               ? settings.implicit_default_step_s
                               : settings.time_step_safety * m_critical_step_s;
  m_time_step_s = settings.time_step.kind == TimeStep::Kind::fixed ? settings.time_step.fixed_s
                                                                   : automatic;
  if (settings.time_step.is_adaptive()) {
    WEFT_CHECK(settings.integrator == Integrator::implicit_euler &&
                   settings.projection.method == ProjectionMethod::fast_projection,
               "the adaptive step follows fast projection's iterations: it needs implicit Euler "
               "and fast projection (the scene reader checks simulation.time_step)");
    // Explicit bending holds only at steps within its stability (bending_in_time_step).
    AdaptiveStepSettings adaptive = settings.time_step.adaptive;
    adaptive.max_step_s =
        std::max(adaptive.min_step_s, std::min(adaptive.max_step_s, m_explicit_stable_step_s));
    m_adaptive = std::make_unique<AdaptiveStep>(adaptive);
    m_time_step_s = adaptive.max_step_s;
  }
  m_integrator_settings.implicit_solve.method = settings.implicit_solve;
  m_integrator_settings.implicit_solve.backend = settings.sparse_backend;
  m_integrator_settings.implicit_solve.cg_tolerance = settings.implicit_cg_tolerance;
  m_integrator_settings.implicit_solve.threads = settings.solver_threads;
  m_integrator_settings.implicit_solve.preconditioner = settings.implicit_cg_preconditioner;
  // Dynamic relaxation: one iteration per step of the explicit integrators' step, with
  // fictitious masses stable at it (sim/integrators/dynamic_relaxation.h).
  m_integrator_settings.relaxation_max_step_s = m_time_step_s;
  m_taut = current_taut_chains();
  for (Index v : m_taut.vertices) m_system.inv_mass[v] = 0.0;
  build_solvers();
}

Simulator::~Simulator() = default;

TautChains Simulator::current_taut_chains() const {
  if (m_settings.projection.method != ProjectionMethod::fast_projection ||
      !m_settings.projection.hold_taut_chains)
    return {};
  std::vector<Index> still, moving;
  for (Index p : m_pinned) {
    const bool moves = std::any_of(m_moving_pins.begin(), m_moving_pins.end(),
                                   [p](const MovingPin& m) { return m.vertex == p; });
    (moves ? moving : still).push_back(p);
  }
  return find_taut_chains(m_mesh, m_state.x, still, moving);
}

void Simulator::build_solvers() {
  if (m_contacts && m_contacts->tension_term()) {  // the old projection's carried tension
    auto& terms = m_system.terms;
    terms.erase(std::remove(terms.begin(), terms.end(), m_contacts->tension_term()), terms.end());
  }
  m_contacts = std::make_unique<ContactsAndConstraints>(m_mesh, m_system.inv_mass, m_settings);
  // The projection's carried tension is one more force term (none before the first projection).
  if (m_contacts->tension_term()) m_system.terms.push_back(m_contacts->tension_term());
  m_integrator_settings.implicit_solve.edges_constrained =
      m_settings.projection.method != ProjectionMethod::none;
  m_integrator_settings.implicit_solve.grid_nu = m_mesh.nu;  // 0 × 0 for a triangle mesh
  m_integrator_settings.implicit_solve.grid_nv = m_mesh.nv;
  m_integrator = make_time_integrator(m_settings.integrator, m_system, m_integrator_settings);
}

void Simulator::hold_taut_chains() {
  TautChains taut = current_taut_chains();
  if (taut.vertices == m_taut.vertices) return;
  for (Index v : m_taut.vertices) m_system.inv_mass[v] = 1.0 / m_system.mass_kg[v];
  for (Index v : taut.vertices) m_system.inv_mass[v] = 0.0;
  m_taut = std::move(taut);
  build_solvers();
}

std::string too_many_steps(double dt_s, double step_s) {
  const double ratio = dt_s / step_s;
  if (ratio <= max_substeps) return {};  // NaN is too many
  std::ostringstream what;
  what << "a time of " << dt_s << " s needs " << ratio << " steps of " << step_s
       << " s, more than the limit of " << max_substeps;
  return what.str();
}

long Simulator::substeps(double dt_s) const {
  if (const std::string why = too_many_steps(dt_s, m_time_step_s); !why.empty())
    throw std::invalid_argument(why);
  const double ratio = dt_s / m_time_step_s;
  return std::max(1L, static_cast<long>(std::ceil(ratio / (1.0 + substep_slack))));
}

void Simulator::advance(double dt_s) {
  if (dt_s <= 0.0) return;
  if (m_adaptive) {
    advance_adaptively(dt_s);
    return;
  }
  const long n = substeps(dt_s);
  if (!m_energy_guard_started) start_energy_guard();
  const double h = dt_s / static_cast<double>(n);
  const double t_end = m_state.time_s + dt_s;
  const long window = failsafe_window_steps(h);
  for (long s = 0; s < n; ++s)
    attempt_step(h, /*may_reject=*/false, /*ends_window=*/(s + 1) % window == 0 || s + 1 == n);
  m_state.time_s = t_end;  // no drift from summing substeps
  check_growth();
}

void Simulator::advance_adaptively(double dt_s) {
  if (!m_energy_guard_started) start_energy_guard();
  const double t_end = m_state.time_s + dt_s;
  double remaining = dt_s;
  long attempts = 0;
  while (remaining > 0.0) {
    if (static_cast<double>(++attempts) > max_substeps)
      throw std::invalid_argument("the adaptive step took more than " +
                                  std::to_string(static_cast<long>(max_substeps)) +
                                  " steps for one advance");
    const double h = m_adaptive->next_step(remaining);
    if (!attempt_step(h, /*may_reject=*/true)) continue;
    // The last step ends exactly at t_end (no drift from summing steps).
    remaining = h < remaining ? t_end - m_state.time_s : 0.0;
    if (remaining <= 1e-12 * dt_s) remaining = 0.0;
  }
  m_state.time_s = t_end;
  check_growth();
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
  hold_taut_chains();  // pins given closer together leave a chain slack
}

void Simulator::set_pin_path(const std::vector<Index>& vertices, const PinPath& path) {
  for (Index v : vertices) {
    if (std::find(m_pinned.begin(), m_pinned.end(), v) == m_pinned.end())
      throw std::invalid_argument("vertex " + std::to_string(v) + " is not pinned: only pins move");
  }
  if (!path.moves()) return;
  m_pin_paths.push_back(path);
  for (Index v : vertices) m_moving_pins.push_back({v, m_pin_paths.size() - 1});
  hold_taut_chains();  // a chain with a moving end is not held
}

const DynamicRelaxation* Simulator::relaxation() const {
  return dynamic_cast<const DynamicRelaxation*>(m_integrator.get());
}

void Simulator::step(double h_s) { attempt_step(h_s, /*may_reject=*/false); }

long Simulator::failsafe_window_steps(double h_s) const {
  const double interval_s = m_settings.self_collision.failsafe_interval_s;
  // Dynamic relaxation's pseudo-time steps seek a rest state, which the windows would move
  // (the static sphere drape settled at 2.0 % strain with them, 0.8 % without).
  if (!m_contacts->impact_zones() || m_settings.remesh.enabled ||
      m_settings.integrator == Integrator::dynamic_relaxation || !(interval_s > h_s))
    return 1;
  return std::max(1L, static_cast<long>(std::floor(interval_s / h_s * (1.0 + 1e-12))));
}

bool Simulator::attempt_step(double h_s, bool may_reject, bool ends_window) {
  const double t0 = m_state.time_s, t1 = t0 + h_s;
  m_x_start = m_state.x;
  if (may_reject) m_v_start = m_state.v;
  m_timers.time(Phase::pins, [&] { drive_pins(h_s); });
  if (m_settings.resting_contacts && m_settings.integrator == Integrator::implicit_euler)
    m_timers.time(Phase::collide, [&] { m_contacts->resting_contacts(m_state.x, m_system.contacts); });
  const StepReport integrated =
      m_timers.time(Phase::integrate, [&] { return m_integrator->step(m_system, m_state, h_s); });
  m_stats.solve_s += integrated.solve_s;
  if (!integrated.solved) ++m_stats.failed_implicit_solves;
  m_stats.cg_iterations += integrated.cg_iterations;
  m_timers.time(Phase::pins, [&] { place_pins(t1); });
  if (m_adaptive) {
    const double strain = max_edge_strain(m_contacts->projector()->constraints(), m_state.x);
    if (m_adaptive->reject(h_s, strain) && may_reject) {
      m_state.x = m_x_start;
      m_state.v = m_v_start;
      ++m_stats.rejected_steps;
      return false;
    }
  }
  m_timers.time(Phase::obstacles, [&] { m_contacts->pose_obstacles(t0, t1); });
  const long iterations_before = m_stats.projection_iterations;
  const long unconverged_before = m_stats.unconverged_steps;
  if (m_window_steps == 0) m_window_start = m_x_start;
  ++m_window_steps;
  m_window_s += h_s;
  const bool corrected = m_contacts->resolve(m_x_start, m_state.x, h_s, m_timers, m_stats,
                                             ends_window ? &m_window_start : nullptr);
  if (m_adaptive)
    m_adaptive->accept(h_s, static_cast<int>(m_stats.projection_iterations - iterations_before),
                       m_stats.unconverged_steps == unconverged_before);
  m_timers.time(Phase::filter, [&] {
    filter_velocities(corrected, integrated.kinetic_reset, h_s);
    if (ends_window) filter_window_velocities(integrated.kinetic_reset);
  });
  m_state.time_s = t1;
  ++m_steps;
  m_stats.min_step_s = m_stats.steps == 0 ? h_s : std::min(m_stats.min_step_s, h_s);
  m_stats.max_step_s = std::max(m_stats.max_step_s, h_s);
  ++m_stats.steps;
  m_timers.time(Phase::check, [&] { check_finite(); });
  if (m_settings.remesh.enabled && m_steps % m_settings.remesh.every_steps == 0)
    m_timers.time(Phase::remesh, [&] {
      if (remesh_due()) remesh_now();
    });
  return true;
}

// At a check (every every_steps steps): always, or with an indicator threshold when seed 002's
// criterion max |κ| h² has passed indicator × c (its largest value goes to the statistics).
// With `coarsen`, also when the refinement excess has grown `coarsen` times above its value
// just after the last remesh (before the first: at the first check): the cloth flattened under
// a mesh made for folds.
bool Simulator::remesh_due() {
  const RemeshSettings& r = m_settings.remesh;
  if (r.indicator <= 0.0) return true;
  const ClothRemeshCriteria criteria = cloth_remesh_criteria(m_mesh, m_state.x, r);
  m_stats.max_remesh_indicator_m = std::max(m_stats.max_remesh_indicator_m, criteria.indicator_m);
  if (criteria.indicator_m > r.indicator * r.c_m) return true;
  if (r.coarsen <= 0.0) return false;
  if (!m_excess_reference) {
    m_excess_reference = criteria.excess;
    return false;
  }
  m_stats.max_remesh_excess = std::max(m_stats.max_remesh_excess, criteria.excess / *m_excess_reference);
  if (criteria.excess <= r.coarsen * *m_excess_reference) return false;
  ++m_stats.coarsenings;
  return true;
}

void Simulator::remesh_now() {
  check_remesh_settings(m_mesh, m_settings);
  if (!m_settings.remesh.enabled)
    throw std::invalid_argument("remesh_now: simulation.remesh is not enabled");
  const double energy_before_J = diagnostics().total_energy_J();
  RemeshedCloth cloth = remesh_cloth(m_mesh, m_state.x, m_state.v, m_initial_x, m_pinned,
                                     m_settings.remesh);
  const auto renumber = [&](Index& v) {
    v = cloth.old_to_new[static_cast<std::size_t>(v)];  // pins are kept: never −1
  };
  for (Index& p : m_pinned) renumber(p);
  for (MovingPin& p : m_moving_pins) renumber(p.vertex);
  m_mesh = std::move(cloth.mesh);
  m_state.x = std::move(cloth.x);
  m_state.v = std::move(cloth.v);
  m_initial_x = std::move(cloth.initial_x);
  rebuild_for_mesh();
  relax_new_vertices(cloth.old_to_new);
  // The coarsening criterion's reference: the new mesh's excess for the curvature it was made for.
  if (m_settings.remesh.coarsen > 0.0)
    m_excess_reference = cloth_remesh_criteria(m_mesh, m_state.x, m_settings.remesh).excess;
  // The energy guard (check_growth) watches what the dynamics gain; the transfer's own change of
  // energy (new vertices strained where the old mesh did not resolve the curvature,
  // docs/remeshing.md) and the relaxation's are the remesh's, so the reference moves by them.
  const double jump_J = diagnostics().total_energy_J() - energy_before_J;
  if (m_start_energy_J) *m_start_energy_J += jump_J;
  m_stats.remesh_energy_J += jump_J;
  ++m_remeshes;
  ++m_stats.remeshes;
}

void Simulator::rebuild_for_mesh() {
  m_system = make_system(m_mesh, m_material, m_pinned, m_settings);
  m_system.timers = &m_timers;
  m_warp_weft_edges = make_edge_constraints(m_mesh, ConstrainedEdges::warp_weft,
                                            Eigen::VectorXd::Ones(m_mesh.vertex_count()));
  m_critical_step_s = critical_step_s(m_system);
  m_explicit_stable_step_s = m_settings.time_step_safety * explicit_stiffness_step_s(m_system);
  m_taut = {};  // none without fast projection
  build_solvers();
}

// The new vertices are held by nothing but the kept old ones: where the cloth folds more sharply
// than the old mesh resolved, the transfer leaves them strained (1 J of membrane energy on the
// disc drape's first remesh, docs/remeshing.md), which the dynamics would turn into motion.
void Simulator::relax_new_vertices(const std::vector<Index>& old_to_new) {
  if (m_settings.remesh.relax_steps <= 0) return;
  // The transfer interpolates across obstacles' edges too (a coarse triangle over the
  // pedestal's rim puts new vertices inside its corner): the push-out the next step would do
  // is part of each trial, so that those vertices end on the surface, relaxed, rather than
  // thrown out of it by the next step.
  StepStatistics scratch;
  const auto push_out = [&](Matrix3X& x) {
    const Matrix3X start = x;
    m_contacts->resolve(start, x, m_time_step_s, m_timers, scratch, &start);
  };
  push_out(m_state.x);
  std::vector<char> free(static_cast<std::size_t>(m_state.x.rows()), 1);
  for (Index k : old_to_new)
    if (k >= 0) free[static_cast<std::size_t>(k)] = 0;
  std::vector<ObstacleContact> resting;
  m_contacts->resting_contacts(m_state.x, resting);
  for (const ObstacleContact& c : resting) free[static_cast<std::size_t>(c.vertex)] = 0;
  relax_vertices(m_system, free, m_state.x, static_cast<int>(m_settings.remesh.relax_steps),
                 m_time_step_s, m_integrator_settings.implicit_solve, push_out);
}

// Every integrator leaves a pinned vertex's velocity as it is (zero acceleration), so the
// velocity that reaches the path's position at t + h carries it there; place_pins() then puts
// it there exactly (not x + h v).
void Simulator::drive_pins(double h_s) {
  for (const MovingPin& p : m_moving_pins)
    m_state.v.row(p.vertex) = (pin_position(p, m_state.time_s + h_s) - m_state.x.row(p.vertex)) / h_s;
}

void Simulator::place_pins(double time_s) {
  for (const MovingPin& p : m_moving_pins) m_state.x.row(p.vertex) = pin_position(p, time_s);
}

Eigen::RowVector3d Simulator::pin_position(const MovingPin& pin, double time_s) const {
  return m_initial_x.row(pin.vertex) + m_pin_paths[pin.path].offset_at(time_s).transpose();
}

// Velocity filter (seed 000): after a correction, the velocity that carries x_n to the
// corrected x_{n+1}; after a kinetic-damping reset of dynamic relaxation, rest.
void Simulator::filter_velocities(bool corrected, bool kinetic_reset, double h_s) {
  if (corrected) m_state.v = (m_state.x - m_x_start) / h_s;
  if (kinetic_reset) m_state.v.setZero();
}

void Simulator::filter_window_velocities(bool kinetic_reset) {
  const ImpactZones* zones = m_contacts->impact_zones();
  if (zones && m_window_steps > 1 && !kinetic_reset)
    for (const Index v : zones->zone_vertices())
      if (m_system.inv_mass[v] > 0.0)  // pins keep the velocity their path gives
        m_state.v.row(v) = (m_state.x.row(v) - m_window_start.row(v)) / m_window_s;
  m_window_steps = 0;
  m_window_s = 0.0;
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

// At the first advance(), for a passive cloth: the energy check_growth() compares with.
void Simulator::start_energy_guard() {
  m_energy_guard_started = true;
  // Nothing feeds energy in. Not with constraints either: a projection that cannot converge
  // (the locking triangle-edge constraints) leaves its best iterate, energy and all.
  const bool passive = m_moving_pins.empty() && !m_settings.aero.enabled &&
                       !any_moves(m_settings.obstacle_motions) &&
                       m_settings.projection.method == ProjectionMethod::none;
  if (!passive) return;
  double mass_kg = 0.0;
  for (Index i = 0; i < m_state.x.rows(); ++i)
    if (m_mesh.is_used(i)) mass_kg += m_system.mass_kg[i];
  const double diagonal_m = (m_state.x.colwise().maxCoeff() - m_state.x.colwise().minCoeff()).norm();
  const Diagnostics start = diagnostics();
  m_start_energy_J = start.total_energy_J();
  m_energy_margin_J = mass_kg * m_settings.gravity_m_s2.norm() * diagonal_m + 0.5 * mass_kg +
                      start.kinetic_energy_J + std::abs(start.elastic_energy_J);
}

// A blow-up that stays finite (a step far above the critical one can swing the cloth to
// 1000 % strain at bounded speed): the strain limit, and energy a passive cloth cannot gain;
// and energies that overflow at finite positions.
void Simulator::check_growth() const {
  for (const EdgeConstraint& e : m_warp_weft_edges) {
    const double strain = std::abs(edge_strain(m_state.x.row(e.a), m_state.x.row(e.b), e.rest_m));
    if (!(strain > m_settings.max_strain)) continue;
    std::ostringstream q;
    q << "the edge from vertex " << e.a << " to vertex " << e.b << " is strained "
      << 100.0 * strain << " % (limit " << 100.0 * m_settings.max_strain
      << " %; try a smaller time_step)";
    throw DivergenceError(m_steps, m_state.time_s, q.str());
  }
  // Energies past what a double holds (a density or stiffness near 1e308) at finite positions:
  // no non-finite number may reach stats.csv or another output.
  const Diagnostics now = diagnostics();
  const std::pair<const char*, double> quantities[] = {
      {"kinetic energy", now.kinetic_energy_J}, {"elastic energy", now.elastic_energy_J},
      {"gravity energy", now.gravity_energy_J}, {"total energy", now.total_energy_J()},
      {"mean strain", now.mean_strain}};
  for (const auto& [name, value] : quantities) {
    if (std::isfinite(value)) continue;
    std::ostringstream q;
    q << "the " << name << " is " << value << " (beyond what a double holds: is the density or "
      << "a stiffness absurd?)";
    throw DivergenceError(m_steps, m_state.time_s, q.str());
  }
  if (!m_start_energy_J) return;
  const double gain_J = now.total_energy_J() - *m_start_energy_J;
  if (gain_J > m_energy_margin_J) {
    Index fastest = 0;
    m_state.v.rowwise().squaredNorm().maxCoeff(&fastest);
    std::ostringstream q;
    q << "the total energy grew by " << gain_J << " J since the start, more than the "
      << m_energy_margin_J << " J a cloth with still pins and obstacles can gain (fastest: vertex "
      << fastest << " at " << m_state.v.row(fastest).norm() << " m/s; try a smaller time_step)";
    throw DivergenceError(m_steps, m_state.time_s, q.str());
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
    d.kinetic_energy_J += 0.5 * m_system.mass_kg[i] * v2;
    d.max_speed_m_s = std::max(d.max_speed_m_s, std::sqrt(v2));
    d.gravity_energy_J -= m_system.mass_kg[i] * m_state.x.row(i).dot(m_settings.gravity_m_s2.transpose());
  }
  d.elastic_energy_J = m_system.energy(m_state.x);
  d.max_strain = max_edge_strain(m_warp_weft_edges, m_state.x);
  d.mean_strain = mean_edge_strain(m_warp_weft_edges, m_state.x);
  return d;
}

}  // namespace weft::sim
