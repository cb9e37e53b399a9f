#pragma once
// One interface for every time integrator: step(system, state, h) advances the positions and
// velocities of `state` by h seconds under the forces of `system` (sim/system.h) and reports
// what the step did. The explicit steppers (explicit_steppers.h), implicit Euler
// (implicit_euler.h) and dynamic relaxation (dynamic_relaxation.h) implement it;
// make_time_integrator() makes the one a scene names.

#include <memory>

#include "base/enum_names.h"
#include "sim/integrators/integrator.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/state.h"
#include "sim/state_archive.h"
#include "sim/system.h"

namespace weft::sim {

// What one step did.
struct StepReport {
  bool solved = true;          // implicit Euler: false when the linear solve failed (v kept)
  double solve_s = 0.0;        // implicit Euler: assembly, factorization and solve, s
  int cg_iterations = 0;       // implicit Euler by conjugate gradients
  bool kinetic_reset = false;  // dynamic relaxation: a kinetic-damping reset (v is now 0)
  int held_contacts = 0;       // implicit Euler: resting contacts held (System::contacts)
};

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  virtual Integrator method() const = 0;
  // Advances state.x (m) and state.v (m/s), #V×3, by h_s > 0 seconds; state.time_s is the
  // step's start time (velocity-dependent forces are taken there) and is left to the caller.
  // Pinned vertices (inv_mass 0) keep their velocity and move by h v. Mismatched sizes are a
  // bug (base::InternalError).
  virtual StepReport step(const System& system, State& state, double h_s) = 0;
  // The same on positions and velocities held apart, at time time_s.
  StepReport step(const System& system, Matrix3X& x, Matrix3X& v, double h_s,
                  double time_s = 0.0);
  // What the integrator carries from one step to the next (central difference's last step,
  // conjugate gradients' warm start, dynamic relaxation's restart flag and counts), for a
  // checkpoint; restore_state() reads it back into an integrator made for the same system.
  virtual void save_state(StateWriter& out) const = 0;
  virtual void restore_state(StateReader& in) = 0;
};

// How implicit Euler solves each step's linear system: a sparse direct factorization
// (SparseBackend), or conjugate gradients preconditioned by block Jacobi or a grid multigrid
// (CgPreconditioner; sim/linear/block_conjugate_gradient.h), warm-started from the previous step's Δv and stopped
// at a relative residual ‖r‖/‖b‖ ≤ tolerance (inexact Newton: cheaper per step on large meshes;
// the step's accuracy is then that of the residual).
enum class ImplicitSolve { direct, conjugate_gradient };

inline constexpr base::EnumNames<ImplicitSolve, 2> implicit_solve_names{
    {{ImplicitSolve::direct, "direct"}, {ImplicitSolve::conjugate_gradient, "conjugate_gradient"}}};

// Conjugate gradients' preconditioner (sim/linear/block_conjugate_gradient.h): a multigrid
// V-cycle on the cloth's warp/weft grid, exact solves along its lines (grid_line_preconditioner.h;
// either is block Jacobi on a mesh without a grid), block Jacobi, or automatic: the multigrid on
// grids of at least kMultigridMinVertices vertices, where it was measured to pay
// (docs/benchmarks.md, "Multigrid for the implicit step"), on smaller grids of an inextensible
// cloth block Jacobi and the lines for the solves it would make slow ("Line solves for the
// implicit step", "The lines only for slow solves"), block Jacobi otherwise.
enum class CgPreconditioner { automatic, multigrid, lines, block_jacobi };
inline constexpr base::EnumNames<CgPreconditioner, 4> cg_preconditioner_names{
    {{CgPreconditioner::automatic, "auto"},
     {CgPreconditioner::multigrid, "multigrid"},
     {CgPreconditioner::lines, "lines"},
     {CgPreconditioner::block_jacobi, "block_jacobi"}}};
inline constexpr Index kMultigridMinVertices = 150 * 150;

struct ImplicitSolveSettings {
  ImplicitSolve method = ImplicitSolve::direct;
  SparseBackend backend = default_sparse_backend();  // direct
  double cg_tolerance = 1e-4;                        // conjugate gradients: relative residual
  int cg_max_iterations = 200;
  // Conjugate gradients: threads of the matrix–vector product (0: all hardware threads). The
  // result is the same bits for any number.
  int threads = 0;
  CgPreconditioner preconditioner = CgPreconditioner::automatic;
  // The cloth's warp/weft grid, vertex (i, j) at j·grid_nu + i; 0 × 0: none (a triangle mesh).
  Index grid_nu = 0, grid_nv = 0;
  // Whether the cloth's edges are held by a projection (its shear springs are then the stiffest
  // couplings in the matrix), which "auto" reads.
  bool edges_constrained = false;
};

// Whether conjugate gradients use the multigrid for these settings: asked for, or automatic on
// a grid of at least kMultigridMinVertices vertices. (A grid the hierarchy cannot coarsen still
// falls back to block Jacobi, BlockConjugateGradient::analyze.)
inline bool uses_multigrid(const ImplicitSolveSettings& s) {
  return s.preconditioner == CgPreconditioner::multigrid ||
         (s.preconditioner == CgPreconditioner::automatic &&
          s.grid_nu * s.grid_nv >= kMultigridMinVertices);
}

// Whether conjugate gradients use the line preconditioner: asked for, or automatic on a grid
// below the multigrid's size whose edges are held by a projection, where it was measured to pay
// (a mass-spring drape ran 1.25 times as long with it). Without a grid: block Jacobi.
inline bool uses_lines(const ImplicitSolveSettings& s) {
  return s.grid_nu > 0 && s.grid_nv > 0 &&
         (s.preconditioner == CgPreconditioner::lines ||
          (s.preconditioner == CgPreconditioner::automatic && s.edges_constrained &&
           !uses_multigrid(s)));
}

// Whether the lines are taken only for the solves block Jacobi would make slow
// (BlockConjugateGradient::GridPreconditioner::lines_when_slow): when "auto" takes them.
inline bool lines_when_slow(const ImplicitSolveSettings& s) {
  return uses_lines(s) && s.preconditioner == CgPreconditioner::automatic;
}

// The preconditioner conjugate gradients use for these settings, as --explain names it: its
// scene name, or "block_jacobi, lines when slow" where "auto" takes the lines for slow solves.
inline const char* preconditioner_in_use(const ImplicitSolveSettings& s) {
  if (uses_multigrid(s) && s.grid_nu > 0) return "multigrid";
  if (lines_when_slow(s)) return "block_jacobi, lines when slow";
  return uses_lines(s) ? "lines" : "block_jacobi";
}

struct IntegratorSettings {
  ImplicitSolveSettings implicit_solve;  // implicit_euler
  double relaxation_max_step_s = 0.0;    // dynamic_relaxation: fictitious masses stable up to it
};

// The integrator `method` for `system` (whose masses, pins and terms fix its structure: step
// it with that system). Misuse is a bug (base::InternalError).
std::unique_ptr<TimeIntegrator> make_time_integrator(Integrator method, const System& system,
                                                     const IntegratorSettings& settings = {});

}  // namespace weft::sim
