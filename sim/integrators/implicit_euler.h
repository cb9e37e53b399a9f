#pragma once
// Backward (implicit) Euler, one Newton step per time step (Baraff & Witkin 1998): with
// K = −∂f/∂x of the springs and of the continuum force terms (sim/force_term.h; both
// PSD-projected) and mass damping α,
//   (M (1 + h α) + h² K) Δv = h (f(x_n) − α M v_n − h K v_n) + h M g,
//   v_{n+1} = v_n + Δv,   x_{n+1} = x_n + h v_{n+1}.
// The mass-spring model's angular bending enters the right-hand side only (its stiffness is
// small: see docs/models.md); a force term without stiffness likewise.
// Optional tension edges carry the previous step's constraint forces (carried_tension.h): a
// tension k > 0 adds the force −k (x_b − x_a) on b and the stiffness k I to K.
// Pinned vertices (inv_mass = 0) keep v = 0. The sparsity pattern of the system matrix is
// fixed by the mesh and analysed once.

#include <memory>

#include "sim/constraints/projection.h"
#include "sim/force_term.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/mass_spring.h"
#include "sim/types.h"

namespace weft::sim {

struct ImplicitStepResult {
  bool solved = true;      // false: the factorization failed (or CG broke down); v unchanged
  double solve_s = 0.0;    // wall time of assembly + factorization + solve
  int cg_iterations = 0;   // conjugate gradients only
};

// How the linear system of each step is solved: a sparse direct factorization (SparseBackend),
// or conjugate gradients with a Jacobi preconditioner, warm-started from the previous step's
// Δv and stopped at a relative residual ‖r‖/‖b‖ ≤ tolerance (inexact Newton: cheaper per step
// on large meshes; the step's accuracy is then that of the residual).
enum class ImplicitSolve { direct, conjugate_gradient };

struct ImplicitSolveSettings {
  ImplicitSolve method = ImplicitSolve::direct;
  SparseBackend backend = default_sparse_backend();  // direct
  double cg_tolerance = 1e-4;                        // conjugate gradients: relative residual
  int cg_max_iterations = 200;
};

class ImplicitEuler {
 public:
  ImplicitEuler(const MassSpringModel& model, Eigen::VectorXd mass_kg, Eigen::VectorXd inv_mass,
                const ImplicitSolveSettings& solve, std::vector<EdgeConstraint> tension_edges = {},
                ForceTerms terms = {});
  ~ImplicitEuler();
  // Replaces v (#V×3, m/s) by v_{n+1} for positions x = x_n; the caller sets x_n + h v_{n+1}.
  // tension_k: one per tension edge (N/m), or empty for none. external_forces (#V×3, N, or
  // empty): forces at (x_n, v_n) taken explicitly, without stiffness (air drag).
  [[nodiscard]] ImplicitStepResult step(const Matrix3X& x, Matrix3X& v, double h_s,
                                        const Vec3& gravity_m_s2, double damping_1_s,
                                        const Eigen::VectorXd& tension_k = Eigen::VectorXd(),
                                        const Matrix3X& external_forces = Matrix3X());

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace weft::sim
