#pragma once
// What a Simulator is asked to simulate besides the cloth itself: the model and integrator,
// gravity and damping, the time step, constraints, obstacles, self-collision and air. The app
// fills it from the scene file (app/scene/scene.cpp); the Simulator turns it into a System, a
// TimeIntegrator and the contacts-and-constraints phase.

#include <optional>
#include <vector>

#include "sim/aerodynamics.h"
#include "sim/cloth_model.h"
#include "sim/collision/obstacle.h"
#include "sim/collision/obstacle_motion.h"
#include "sim/collision/self_collision.h"
#include "sim/constraints/projection.h"
#include "sim/integrators/integrator.h"
#include "sim/integrators/time_integrator.h"
#include "sim/statics/static_settings.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/remesh/transfer.h"
#include "sim/types.h"

namespace weft::sim {

// simulation.time_step: "adaptive" (sim/adaptive_step.h): implicit Euler with fast projection
// only; the step follows the projection's iterations, and a step whose unconstrained
// prediction strains an edge beyond max_prediction_strain is redone shorter.
struct AdaptiveStepSettings {
  double min_step_s = 1.0 / 960.0;
  double max_step_s = 1.0 / 24.0;       // also the first step's length
  double max_prediction_strain = 0.25;  // ε_max
};

// simulation.time_step, one setting with its kind: automatic (empty in the scene, or "auto"),
// a fixed step, or adaptive with its bounds. The scene reader checks it against the integrator,
// the constraints and the frame (app/scene/scene.cpp).
struct TimeStep {
  enum class Kind { automatic, fixed, adaptive };
  Kind kind = Kind::automatic;
  double fixed_s = 0.0;           // Kind::fixed: the step, s
  AdaptiveStepSettings adaptive;  // Kind::adaptive: its bounds and strain target
  bool is_adaptive() const { return kind == Kind::adaptive; }
};
inline TimeStep fixed_time_step(double step_s) { return {TimeStep::Kind::fixed, step_s, {}}; }
inline TimeStep adaptive_time_step(const AdaptiveStepSettings& settings = {}) {
  return {TimeStep::Kind::adaptive, 0.0, settings};
}

// simulation.remesh (docs/remeshing.md): the cloth is meshed anew in material space, graded by
// its curvature (seed 002 eq. 29: h = clamp(√(c/|κ|), h_min, h_max)), positions and velocities
// interpolated onto the new mesh, the boundary and pins kept exactly (sim/cloth_remesh.h):
// after every every_steps-th step, or, with an indicator threshold, only at those checks where
// seed 002's criterion max |κ| h² (eq. 28, §5.2 d) exceeds indicator × c. Off unless enabled;
// a triangle-mesh cloth only (Simulator checks).
struct RemeshSettings {
  bool enabled = false;
  long every_steps = 100;  // steps between two remeshes, or between two indicator checks
  double c_m = 1e-3;       // eq. 29's constant |κ| h², metres
  double h_min_m = 0.005;  // the finest edge, metres
  double h_max_m = 0.05;   // the coarsest edge (flat cloth), metres
  // > 0: remesh only when max |κ| h² > indicator × c (dimensionless, > 1: after a remesh the
  // criterion is about c where the cloth is curved); 0: remesh at every check.
  double indicator = 0.0;
  // > 0 (with indicator): also remesh when the mesh has grown this many times finer than the
  // curvature asks for, relative to just after the last remesh (the cloth flattened under a
  // fine mesh; remesh::refinement_excess); 0: the indicator only refines.
  double coarsen = 0.0;
  // Of positions (sim/remesh/transfer.h); velocities are linear.
  remesh::PositionTransfer transfer = remesh::PositionTransfer::quadratic;
  // Steps relaxing the new vertices after the transfer (the cloth model's elastic energy alone;
  // the kept vertices and those resting on an obstacle held, after the obstacles' push-out:
  // sim/remesh_relaxation.h, Simulator::relax_new_vertices); 0: none (the transfer as it is).
  long relax_steps = 4;
  long max_vertices = 200'000;  // a mesh finer than this is an error, not a frozen run
};

struct SimSettings {
  ClothModel model = ClothModel::mass_spring;  // the forces (sim/cloth_model.h)
  Integrator integrator = Integrator::symplectic_euler;
  Vec3 gravity_m_s2{0.0, 0.0, -9.81};
  double air_damping_1_s = 0.5;        // mass-proportional damping α: f = −α m v (seed 002 eq. 27)
  // The scene's simulation.time_step (app/scene/scene.cpp). Automatic: every explicit integrator: time_step_safety × the critical step 2/ω_max,
  // with ω_max² estimated from a Gershgorin bound on the largest eigenvalue of M⁻¹K (an upper
  // bound, so 1.0 is still stable at rest; measured: the default scene with symplectic Euler is
  // stable up to 1.2 and explodes at 1.5). 2/ω is the limit of symplectic Euler, velocity Verlet
  // and central difference; RK4's is 2√2/ω (not used: the same step keeps a margin); explicit
  // Euler has none on an undamped oscillator. Implicit Euler, unconditionally stable:
  // implicit_default_step_s.
  TimeStep time_step;
  double time_step_safety = 0.8;
  double implicit_default_step_s = 1.0 / 120.0;
  // Implicit Euler with the mass-spring grid: whether its bending stiffness enters the step's
  // matrix. Automatic: when explicit bending would not be stable at the run's steps, h ω > 2
  // (with time_step_safety) with ω² ≤ max_i bound_i / m_i over the bending alone — exact for
  // the out-of-plane checkerboard mode, and fine grids reach it: ω² grows as 1/l⁴. With the
  // adaptive step, explicit bending keeps the steps within that limit instead, unless that
  // would hold them shorter than kExplicitBendingShortestStep × implicit_default_step_s
  // (docs/models.md, "Bending in the time step").
  BendingInStep bending_in_step = BendingInStep::automatic;
  // Measured on the adaptive two-corner hang: explicit bending's steps, held within its limit,
  // cost about a third of the steps with the bending in the matrix, which take 5–6 a frame;
  // explicit bending took 0.80 of the CPU time at 128² (steps ≤ 2.9 ms) and 1.24 at 160²
  // (≤ 1.8 ms), so it pays down to a quarter of 1/120 s (2.1 ms).
  static constexpr double kExplicitBendingShortestStep = 0.25;
  // Divergence guard: a non-finite position or velocity, or any vertex faster than this (an
  // explosion, not physics: free fall reaches 100 m/s only after 10 s).
  double max_speed_m_s = 200.0;
  // Divergence guards for a blow-up that stays finite, checked after each Simulator::advance():
  // a warp or weft edge strained beyond max_strain (5 = 500 %: no fabric; a wool sheet 1000×
  // softer than Kang & Yu's stretches about 170 % under its own weight), and, when nothing
  // feeds energy in (no moving pin or obstacle, no air), a total energy (kinetic + elastic +
  // gravity) grown above its start by more than M |g| D + ½ M (1 m/s)² + the start's kinetic
  // and elastic energy (M the cloth's mass, D its diagonal): damping only takes energy out.
  double max_strain = 5.0;
  // Inextensibility after the unconstrained step (the "project" phase). With a projection
  // method the warp/weft springs are replaced by constraints.
  ProjectionSettings projection;
  SparseBackend sparse_backend = default_sparse_backend();  // implicit Euler and fast projection
  // Implicit Euler's linear solve: direct (sparse_backend) or conjugate gradients to a relative
  // residual of implicit_cg_tolerance (see ImplicitSolveSettings).
  ImplicitSolve implicit_solve = ImplicitSolve::direct;
  double implicit_cg_tolerance = 1e-4;
  CgPreconditioner implicit_cg_preconditioner = CgPreconditioner::automatic;
  // Threads of the conjugate gradients' matrix–vector product (0: all hardware threads). Never
  // changes a bit of the result (`weft run --threads`).
  int solver_threads = 0;
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
  // Implicit Euler: the vertices resting on an obstacle at a step's start and pressed into it
  // have their normal velocity held at zero within the solve (System::contacts), so that the
  // obstacle's normal force acts on the whole cloth in the solve instead of only on the
  // vertices the push-out moves after it (docs/collisions.md, "Resting contacts"). Off by
  // default for now: a held vertex gets friction only from what the push-out still moves.
  bool resting_contacts = false;
  // The cloth against itself (the "collide" phase, after the obstacles; off unless enabled):
  // sim/collision/self_collision.h.
  SelfCollisionSettings self_collision;
  // Air drag on every triangle and an optional wind field (sim/aerodynamics.h); off unless
  // enabled. The existing air_damping is separate (a mass-proportional damping).
  AeroSettings aero;
  // Adaptive remeshing during the run; off unless enabled.
  RemeshSettings remesh;
  // How a static solve (weft run --rest, weft measure --static, weft fit) finds the rest shape:
  // sim/statics/static_equilibrium.h.
  StaticSettings statics;
};

}  // namespace weft::sim
