#pragma once
// The time stepper: Simulator::step() is a list of named, timed phases.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/adaptive_step.h"
#include "sim/constraints/taut_chains.h"
#include "sim/contacts_and_constraints.h"
#include "sim/diagnostics.h"
#include "sim/grid.h"
#include "sim/integrators/dynamic_relaxation.h"
#include "sim/integrators/time_integrator.h"
#include "sim/material/material.h"
#include "sim/pin_motion.h"
#include "sim/sim_settings.h"
#include "sim/state.h"
#include "sim/state_archive.h"
#include "sim/statics/static_equilibrium.h"
#include "sim/system.h"

namespace weft::sim {

// Thrown when the simulation diverges; carries where and what.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(long step, double time_s, std::string quantity);
  long step() const { return m_step; }
  double time_s() const { return m_time_s; }
  const std::string& quantity() const { return m_quantity; }

 private:
  long m_step;
  double m_time_s;
  std::string m_quantity;
};

// The most steps one advance() takes (a frame, for the commands).
inline constexpr double max_substeps = 1e6;
// The relative excess over time_step() that Simulator::substeps() allows a step (10 µs in 1 s).
inline constexpr double substep_slack = 1e-5;
// Why a time of dt_s cannot be taken in steps of step_s ("a time of … needs … steps of … s,
// more than the limit of 1e+06"), or empty when it can.
std::string too_many_steps(double dt_s, double step_s);

// Why a scene with these settings cannot be solved statically (constraints instead of stretch
// springs, moving obstacles, air, remeshing), naming the setting; empty when it can.
std::string static_solve_refusal(const SimSettings& settings);

// A cloth simulation: the System (masses, gravity, damping, force terms, pins) of a mesh and
// material, the TimeIntegrator the settings name, and the contacts-and-constraints phase.
// Not movable (the System and the phase refer to its members).
class Simulator {
 public:
  Simulator(ClothMesh mesh, const Material& material, std::vector<Index> pinned,
            const SimSettings& settings);
  ~Simulator();

  // Advances by exactly dt_s, in equal substeps of at most time_step(), or with the adaptive
  // step (sim/adaptive_step.h) in steps it chooses. Throws DivergenceError, and
  // std::invalid_argument as substeps().
  void advance(double dt_s);
  // The number of equal steps, each at most time_step(), that advance(dt_s) takes: at least 1.
  // A step up to substep_slack longer than time_step() counts as fitting, so that a step typed
  // in decimals (0.0208333 s for 1/48 s) splits a 1/24 s frame into 2 steps, not 3.
  // Throws std::invalid_argument when that is more than max_substeps (a time step of 1e-300 s,
  // or the automatic step of an absurd density), rather than overflowing to none.
  long substeps(double dt_s) const;
  // Moves these pinned vertices along the path (offsets from their rest positions, at the
  // simulated time). Throws std::invalid_argument naming a vertex that is not pinned.
  void set_pin_path(const std::vector<Index>& vertices, const PinPath& path);
  // One step of h seconds, as named, timed phases: drive pins → integrate → place pins → move
  // obstacles → contacts and constraints → velocity filter → check → remesh (with
  // simulation.remesh, after every every_steps-th step; with its indicator, only when seed
  // 002's criterion max |κ| h² has passed indicator × c). With the adaptive step, the
  // step is never rejected here, but its prediction still sets the next planned step.
  void step(double h_s);
  // Starts the cloth from these positions (#V×3, m) instead of its flat rest state, at rest:
  // e.g. a tension-field fold pattern (sim/folds/). Pins hold their vertices where they are
  // given here, and moving pins' paths are offsets from there. Throws std::invalid_argument
  // after the first step, for a wrong size, or naming a vertex with a non-finite position.
  void set_initial_positions(const Matrix3X& x);

  // Moves the cloth from where it is to its static equilibrium under gravity, its force terms,
  // its pins and the obstacles where they stand (sim/statics/static_equilibrium.h); velocities
  // are zeroed, time does not advance. Throws std::invalid_argument when the scene has what a
  // static solve cannot hold (static_solve_refusal, moving pins).
  StaticResult solve_static(const StaticSettings& settings);

  // Remeshes the cloth now (sim/cloth_remesh.h), relaxes the new vertices (simulation.remesh.relax:
  // the obstacles' push-out, then steps of the elastic terms alone with the kept vertices and
  // those on an obstacle held, sim/remesh_relaxation.h) and rebuilds everything made from the mesh:
  // masses, force terms, pins' and moving pins' vertex indices, the contacts and constraints
  // (self-collision's structures included) and the integrator, whose memory starts afresh.
  // The vertex count changes: state(), mesh(), pinned() and masses_kg() are the new mesh's.
  // Throws std::invalid_argument as check_remesh_settings unless simulation.remesh is enabled
  // and applies, and from the remesher.
  void remesh_now();
  long remesh_count() const { return m_remeshes; }
  // Whether a remesh check (every every_steps steps) remeshes now: always without an indicator
  // threshold, else when cloth_remesh_indicator_m of the current positions passes it (recorded
  // in the step statistics' max_remesh_indicator_m), or, with simulation.remesh.coarsen, when
  // the mesh has grown that many times finer than the curvature asks for since it was made
  // (the ratio in max_remesh_excess).
  bool remesh_due();

  const State& state() const { return m_state; }
  // The cloth's current mesh: the scene's until the first remesh. The object stays the same
  // (a reference to it stays valid) while its contents change with each remesh.
  const ClothMesh& mesh() const { return m_mesh; }
  // The physical system stepped: masses, gravity, damping, every force term.
  const System& system() const { return m_system; }
  const Eigen::VectorXd& masses_kg() const { return m_system.mass_kg; }
  const std::vector<Index>& pinned() const { return m_pinned; }
  // Free vertices held still because they lie on a chain pulled straight between two still pins
  // at its rest length (fast projection only; sim/constraints/taut_chains.h). Decided at
  // construction and again when initial positions or pin paths are set.
  const TautChains& taut_chains() const { return m_taut; }
  // The fixed step, or the adaptive step's longest.
  double time_step() const { return m_time_step_s; }
  // The adaptive step's controller; null unless simulation.time_step is "adaptive".
  const AdaptiveStep* adaptive_step() const { return m_adaptive.get(); }
  double critical_time_step() const { return m_critical_step_s; }
  // Implicit Euler: the longest step at which the stiffness left out of its matrix (the grid's
  // bending, when explicit) is stable, with time_step_safety; infinity when none is left out.
  double explicit_stable_time_step() const { return m_explicit_stable_step_s; }
  long steps_taken() const { return m_steps; }
  Diagnostics diagnostics() const;
  const PhaseTimers& timers() const { return m_timers; }
  // Self-collision's broad and narrow phase (their times, candidate lists); null when off.
  const SelfCollision* self_collision() const { return m_contacts->self_collision(); }
  // Self-collision's failsafe (its candidate list's rebuilds); null when off.
  const ImpactZones* impact_zones() const { return m_contacts->impact_zones(); }
  // dynamic_relaxation: where the relaxation stands (residual, kinetic peaks); null otherwise.
  const DynamicRelaxation* relaxation() const;
  // One line per phase of a step (integrate, forces, project, collide, pins): which terms and
  // methods this simulation runs, with their sizes — only what the scene needs is assembled.
  std::vector<std::string> explain() const;
  StepStatistics take_step_statistics();

  // Everything the simulation carries from one step to the next (sim/simulator_state.cpp):
  // positions, velocities, time, step count, the energy guard, the step statistics not yet
  // taken, the integrator's, projector's, carried tension's and self-collision's memory; and,
  // once the cloth has been remeshed, its current mesh (sim/cloth_mesh_archive.h), the pins'
  // and moving pins' vertex numbers on it and the remesh count. A Simulator made from the same
  // scene (and pin paths) and restored from it continues with the same bits as the one saved:
  // restoring a remeshed state rebuilds everything made from the mesh, as remesh_now() does.
  // restore_state() throws StateArchiveError when the bytes do not fit this simulation
  // (another mesh, integrator or setting; a remeshed state into a simulation without
  // simulation.remesh or with another number of pins or moving pins).
  void save_state(StateWriter& out) const;
  void restore_state(StateReader& in);

 private:
  struct MovingPin {
    Index vertex;
    std::size_t path;  // index into m_pin_paths
  };
  Eigen::RowVector3d pin_position(const MovingPin& pin, double time_s) const;
  void drive_pins(double h_s);  // sets moving pins' velocities to reach their path at t + h
  void place_pins(double time_s);  // puts moving pins exactly on their path
  // step(h_s); with may_reject and the adaptive step, a step whose prediction strays too far is
  // undone (positions, velocities) before its contacts and constraints: returns false.
  // ends_window: the self-collision failsafe runs at the end of this step, over the window of
  // steps since the last (SelfCollisionSettings::failsafe_interval_s).
  bool attempt_step(double h_s, bool may_reject, bool ends_window = true);
  void advance_adaptively(double dt_s);
  // Steps of h_s per failsafe window in advance(): 1 unless the interval holds several.
  long failsafe_window_steps(double h_s) const;
  void filter_velocities(bool corrected, bool kinetic_reset, double h_s);
  // After a failsafe over a window of several steps: the zones' vertices get the zone's mean
  // velocity over the window instead of the last step's jump to it (none after a kinetic
  // reset). Closes the window.
  void filter_window_velocities(bool kinetic_reset);
  void check_finite() const;
  void start_energy_guard();
  void check_growth() const;
  std::string explain_integrate() const;
  std::string explain_forces() const;
  // Finds the taut chains at the current positions and, when they changed, holds their vertices
  // (inverse mass 0) and rebuilds what depends on which vertices are free: the contacts and
  // constraints (the projection's pattern) and the integrator (the implicit matrix's).
  void hold_taut_chains();
  TautChains current_taut_chains() const;  // none unless fast projection

  void build_solvers();
  // After m_mesh and m_pinned changed (a remesh, a restored remeshed state): masses, force
  // terms, the strain diagnostic's edges, the critical step, the contacts and constraints and
  // the integrator, whose memory starts afresh.
  void rebuild_for_mesh();
  // After a remesh: simulation.remesh.relax steps of the elastic terms alone over the new
  // vertices (old_to_new: the remesh's), the kept vertices and those resting on an obstacle held
  // (sim/remesh_relaxation.h).
  void relax_new_vertices(const std::vector<Index>& old_to_new);

  ClothMesh m_mesh;
  Material m_material;  // to rebuild the force terms after a remesh
  SimSettings m_settings;
  std::vector<Index> m_pinned;
  System m_system;
  TautChains m_taut;
  std::unique_ptr<ContactsAndConstraints> m_contacts;  // refers to m_system.inv_mass
  IntegratorSettings m_integrator_settings;
  std::unique_ptr<TimeIntegrator> m_integrator;
  std::vector<MovingPin> m_moving_pins;
  std::vector<PinPath> m_pin_paths;
  Matrix3X m_initial_x;  // #V×3: where the cloth started, from which moving pins are offset
  std::vector<EdgeConstraint> m_warp_weft_edges;  // for the strain diagnostic
  State m_state;
  Matrix3X m_x_start;  // #V×3 start-of-step positions: velocity filter, friction
  Matrix3X m_v_start;  // #V×3 start-of-step velocities, kept for an adaptive step's rejection
  // The failsafe's window: the positions at its start, its steps so far and their duration.
  Matrix3X m_window_start;
  long m_window_steps = 0;
  double m_window_s = 0.0;
  std::unique_ptr<AdaptiveStep> m_adaptive;
  // The energy guard of check_growth(): the total energy at the first advance() and how much
  // it may grow; none when pins, obstacles or air feed energy in.
  bool m_energy_guard_started = false;
  std::optional<double> m_start_energy_J;
  double m_energy_margin_J = 0.0;
  double m_critical_step_s = 0.0;
  // Implicit Euler: the longest step at which the stiffness left explicit (the grid's bending)
  // is stable, with the safety factor; infinity when all of it is in the matrix.
  double m_explicit_stable_step_s = 0.0;
  double m_time_step_s = 0.0;
  long m_steps = 0;
  long m_remeshes = 0;
  // simulation.remesh.coarsen: the refinement excess just after the last remesh (the scene's
  // mesh: at the first check).
  std::optional<double> m_excess_reference;
  StepStatistics m_stats;
  PhaseTimers m_timers;
};

}  // namespace weft::sim
