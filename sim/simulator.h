#pragma once
// The time stepper: Simulator::step() is a list of named, timed phases.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/aerodynamics.h"
#include "sim/cloth_model.h"
#include "sim/collision/obstacle.h"
#include "sim/collision/obstacle_motion.h"
#include "sim/collision/self_collision.h"
#include "sim/constraints/projection.h"
#include "sim/diagnostics.h"
#include "sim/grid.h"
#include "sim/integrators/dynamic_relaxation.h"
#include "sim/integrators/explicit_steppers.h"
#include "sim/integrators/implicit_euler.h"
#include "sim/integrators/integrator.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/mass_spring.h"
#include "sim/material.h"
#include "sim/pin_motion.h"
#include "sim/state.h"

namespace weft::sim {

struct SimSettings {
  ClothModel model = ClothModel::mass_spring;  // the forces (sim/cloth_model.h)
  Integrator integrator = Integrator::symplectic_euler;
  Vec3 gravity_m_s2{0.0, 0.0, -9.81};
  double air_damping_1_s = 0.5;        // mass-proportional damping α: f = −α m v (seed 002 eq. 27)
  // Empty: automatic. Every explicit integrator: time_step_safety × the critical step 2/ω_max,
  // with ω_max² estimated from a Gershgorin bound on the largest eigenvalue of M⁻¹K (an upper
  // bound, so 1.0 is still stable at rest; measured: the default scene with symplectic Euler is
  // stable up to 1.2 and explodes at 1.5). 2/ω is the limit of symplectic Euler, velocity Verlet
  // and central difference; RK4's is 2√2/ω (not used: the same step keeps a margin); explicit
  // Euler has none on an undamped oscillator. Implicit Euler, unconditionally stable:
  // implicit_default_step_s.
  std::optional<double> time_step_s;
  double time_step_safety = 0.8;
  double implicit_default_step_s = 1.0 / 120.0;
  // Divergence guard: a non-finite position or velocity, or any vertex faster than this (an
  // explosion, not physics: free fall reaches 100 m/s only after 10 s).
  double max_speed_m_s = 200.0;
  // Inextensibility after the unconstrained step (the "project" phase). With a projection
  // method the warp/weft springs are replaced by constraints.
  ProjectionSettings projection;
  SparseBackend sparse_backend = default_sparse_backend();  // implicit Euler and fast projection
  // Implicit Euler's linear solve: direct (sparse_backend) or conjugate gradients to a relative
  // residual of implicit_cg_tolerance (see ImplicitSolveSettings).
  ImplicitSolve implicit_solve = ImplicitSolve::direct;
  double implicit_cg_tolerance = 1e-4;
  // Rigid obstacles (the "collide" phase) and how far the cloth keeps from their surfaces.
  std::vector<Obstacle> obstacles;
  // Keyframed motion of the obstacles: empty (none moves) or one per obstacle (an empty
  // ObstacleMotion for one that stays). The collide phase of a step from t to t + h uses the
  // obstacles posed at t + h, with friction relative to their motion over the step.
  std::vector<ObstacleMotion> obstacle_motions;
  double collision_thickness_m = 2e-3;
  // Coulomb friction coefficient μ (dimensionless, ≥ 0) of the cloth against every obstacle,
  // applied by the push-out from the step's start positions (sim/collision/obstacle.h). 0: the
  // frictionless push-out; a cloth rests on a slope of angle θ when μ > tan θ.
  double collision_friction = 0.0;
  // The cloth against itself (the "collide" phase, after the obstacles; off unless enabled):
  // sim/collision/self_collision.h.
  SelfCollisionSettings self_collision;
  // Air drag on every triangle and an optional wind field (sim/aerodynamics.h); off unless
  // enabled. The existing air_damping is separate (a mass-proportional damping).
  AeroSettings aero;
};

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

// What the steps since the last take_step_statistics() did.
struct StepStatistics {
  long steps = 0;
  long projection_iterations = 0;     // summed over steps
  int max_projection_iterations = 0;  // in any one step
  long unconverged_steps = 0;         // steps whose projection missed its tolerance
  double worst_projected_strain = 0.0;
  double solve_s = 0.0;               // linear solves (implicit Euler and fast projection)
  long failed_implicit_solves = 0;
  long cg_iterations = 0;             // implicit Euler by conjugate gradients, summed over steps
  long max_self_contacts = 0;         // self-collision contacts in any one step
};

class Simulator {
 public:
  Simulator(ClothMesh mesh, const Material& material, std::vector<Index> pinned,
            const SimSettings& settings);
  ~Simulator();

  // Advances by exactly dt_s, in equal substeps of at most time_step(). Throws DivergenceError.
  void advance(double dt_s);
  // Moves these pinned vertices along the path (offsets from their rest positions, at the
  // simulated time). Throws std::invalid_argument naming a vertex that is not pinned.
  void set_pin_path(const std::vector<Index>& vertices, const PinPath& path);
  // One step of h seconds: forces → integrate → project → collide → check.
  void step(double h_s);
  // Starts the cloth from these positions (#V×3, m) instead of its flat rest state, at rest:
  // e.g. a tension-field fold pattern (sim/folds/). Pins hold their vertices where they are
  // given here, and moving pins' paths are offsets from there. Throws std::invalid_argument
  // after the first step, for a wrong size, or naming a vertex with a non-finite position.
  void set_initial_positions(const Matrix3X& x);

  const State& state() const { return m_state; }
  const ClothMesh& mesh() const { return m_mesh; }
  const MassSpringModel& model() const { return m_model; }  // empty for continuum models
  const ForceTerms& force_terms() const { return m_terms; }  // continuum models' terms
  const Eigen::VectorXd& masses_kg() const { return m_mass_kg; }
  const std::vector<Index>& pinned() const { return m_pinned; }
  double time_step() const { return m_time_step_s; }
  double critical_time_step() const { return m_critical_step_s; }
  long steps_taken() const { return m_steps; }
  Diagnostics diagnostics() const;
  const PhaseTimers& timers() const { return m_timers; }
  // Self-collision's broad and narrow phase (their times, candidate lists); null when off.
  const SelfCollision* self_collision() const { return m_self.get(); }
  // dynamic_relaxation: where the relaxation stands (residual, kinetic peaks); null otherwise.
  const DynamicRelaxation* relaxation() const { return m_relaxation.get(); }
  // One line per phase of a step (integrate, forces, project, collide, pins): which terms and
  // methods this simulation runs, with their sizes — only what the scene needs is assembled.
  std::vector<std::string> explain() const;
  StepStatistics take_step_statistics();

 private:
  // Springs, bending and carried constraint tension at x, added to f (N): the explicit
  // steppers' internal forces (gravity and air damping are theirs).
  void add_internal_forces(const Matrix3X& x, Matrix3X& f) const;
  void integrate(double h_s);
  void move_pins(double h_s);  // sets moving pins' velocities to reach their path at t + h
  bool carries_tension() const;
  ProjectionResult project(double h_s);  // one projection; carries its tension
  void record_projection(const ProjectionResult& r);  // a step's projections, summed
  bool collide(bool with_friction);
  void pose_obstacles(double t0_s, double t1_s);  // m_posed_obstacles at t1, motions t0 → t1
  static constexpr int kContactRounds = 2;  // push-outs between projections, per step
  void check_finite() const;

  ClothMesh m_mesh;
  SimSettings m_settings;
  MassSpringModel m_model;
  ForceTerms m_terms;
  std::vector<Index> m_pinned;
  struct MovingPin {
    Index vertex;
    std::size_t path;  // index into m_pin_paths
  };
  std::vector<MovingPin> m_moving_pins;
  std::vector<PinPath> m_pin_paths;
  Matrix3X m_initial_x;  // #V×3: where the cloth started, from which moving pins are offset
  Eigen::RowVector3d pin_position(const MovingPin& pin, double time_s) const;
  Eigen::VectorXd m_mass_kg;       // #V lumped masses
  Eigen::VectorXd m_inv_mass;      // #V, 0 for pinned vertices
  std::vector<EdgeConstraint> m_warp_weft_edges;  // for the strain diagnostic
  std::unique_ptr<ConstraintProjector> m_projector;
  Eigen::VectorXd m_tension_k;  // per constraint, N/m: carried constraint force (carried_tension.h)
  std::unique_ptr<ImplicitEuler> m_implicit;   // implicit_euler
  std::unique_ptr<ExplicitStepper> m_explicit;  // every other integrator
  std::unique_ptr<DynamicRelaxation> m_relaxation;  // dynamic_relaxation
  std::unique_ptr<Aerodynamics> m_aero;         // when settings.aero.enabled
  std::unique_ptr<SelfCollision> m_self;        // when settings.self_collision.enabled
  Matrix3X m_aero_forces;                       // #V×3, N: implicit Euler's explicit drag
  State m_state;
  Matrix3X m_x_start;              // #V×3 start-of-step positions: velocity filter, friction
  std::vector<Obstacle> m_posed_obstacles;      // where the collide phase finds the obstacles
  std::vector<RigidPose> m_obstacle_step_motions;  // each one's motion over the step; empty: none
  double m_critical_step_s = 0.0;
  double m_time_step_s = 0.0;
  long m_steps = 0;
  StepStatistics m_stats;
  PhaseTimers m_timers;
};

}  // namespace weft::sim
