#pragma once
// The static equilibrium of a cloth: the positions x that minimise its total potential energy
//   Π(x) = Σ_terms E(x) − Σ_i m_i g·x_i + Σ_i Σ_obstacles ½ k_i (δ − d(x_i))₊²
// over the free vertices (pins fixed), found by Newton's method — what a drape test, a
// cantilever or a hang reads once the cloth has stopped moving, without simulating the motion.
//
// Each iteration solves (K + μ M) p = −∇Π with K the force terms' Hessian plus the contact
// penalties' k n nᵀ, M the lumped masses and μ a Levenberg–Marquardt shift (at least 1e-8 of
// the mean diag(K)/m, which keeps the rigid motions of a pinless or frictionless cloth from
// making K singular; raised ×10 when the factorization fails or p does not descend, lowered ÷3
// after a step taken whole). Far from rest each element's Hessian is projected onto the positive
// semi-definite cone (sim/linear/stiffness_assembly.h): a descent direction whatever the shape.
// Below a residual of 1 (once the first large moves are over) the exact Hessian is tried first:
// positive definite near a stable equilibrium, it converges quadratically where the projected
// one, exact only where nothing is compressed or bent past its rest, converges linearly; when
// it is indefinite (a saddle: the shape is about to buckle) the projected one is used for the
// next 10 iterations. Trying it this early halves the iterations of drape solves.
//
// The step is capped: no vertex moves more than a trust radius (½ the shortest rest edge at
// first, doubled after a step taken whole that it shortened, set to what a backtracked step
// moved: it never exceeds twice the longest step taken), and none nearer an obstacle than its
// distance to that surface (or the thickness δ), so no step jumps through an
// obstacle before its penalty can stop it. Then a backtracking line search takes the longest
// α ≤ 1 with Π(x + α p) ≤ Π(x) + 1e-4 α ∇Πᵀp (Armijo); near the minimum, where Π's decrease is
// below its rounding, a whole step that lowers ‖∇Π‖ is taken on the residual's word. Every
// accepted step lowers Π (or the residual at the end): the iteration cannot diverge.
//
// The factorizations (hundreds per solve) are CHOLMOD's supernodal L Lᵀ through BLAS when weft
// has CHOLMOD (sim/linear/cholmod_solver.h), Eigen's LDLᵀ otherwise.
//
// Contact. An obstacle is a one-sided penalty on the signed distance d of each free vertex to
// its surface, ½ k_i (δ − d)² where d < δ (δ = the collision thickness), with
// k_i = contact_stiffness × m_i |g| / δ: a vertex pressed with a force F sinks F / k_i into the
// layer, 1 % of δ for one that carries 10 times its own weight at the default 1000.
// Frictionless: a static solve has no path along which friction could act. The Hessian keeps k n nᵀ and drops the
// surface's curvature term (still PSD). Self-contact is not modelled (the count of crossing
// edges after the solve says whether it mattered).
//
// Bifurcations. A flat, symmetric start (a Cusick specimen) sits on a symmetric path whose
// buckled branches are lower in energy; which branch the solver takes decides the node count.
// A deterministic imperfection breaks the symmetry: every free vertex is moved at the start by
// a pseudo-random offset of at most `imperfection` × the mean rest edge length, drawn from
// `seed` (the same seed, the same shape, bit for bit). Different seeds sample the branches a
// real specimen's small defects would select: run several and report the spread.
//
// Convergence: the force residual ‖∇Π‖ over the free DOFs relative to the cloth's weight
// ‖M g‖ ≤ tolerance. Velocity-dependent forces (air drag, wind) and constraints are not part of
// Π: the caller refuses scenes that need them.

#include <string>
#include <vector>

#include "sim/collision/obstacle.h"
#include "sim/statics/static_settings.h"
#include "sim/system.h"
#include "sim/types.h"

namespace weft::sim {

struct StaticResult {
  bool converged = false;
  int iterations = 0;
  int factorizations = 0;
  double residual = 0.0;   // ‖∇Π‖ / ‖M g‖ at the end
  double energy_J = 0.0;   // Π at the end
  int contacts = 0;        // vertices inside an obstacle's layer at the end
  std::string stopped;     // why it stopped without converging; empty when converged
};

class StaticEquilibrium {
 public:
  // `system`: masses, gravity, pins (inv_mass 0) and the force terms; obstacles posed where the
  // cloth rests on them; thickness_m = δ > 0; mean and shortest rest edge lengths (m) set the
  // imperfection and the step cap. Bad settings are bugs (WEFT_CHECK).
  StaticEquilibrium(const System& system, std::vector<Obstacle> obstacles, double thickness_m,
                    double mean_edge_m, double shortest_edge_m, const StaticSettings& settings);
  ~StaticEquilibrium();

  // Moves x (#V×3, m) to the equilibrium from where it is, after the imperfection (pins stay).
  StaticResult solve(Matrix3X& x) const;

  // Π(x), J.
  double energy(const Matrix3X& x) const;
  // ∇Π(x) on the free vertices, 0 on the pinned ones, #V×3, N.
  Matrix3X gradient(const Matrix3X& x) const;

 private:
  struct Newton;
  // Adds the contact penalties' Hessians k n nᵀ to the assembled matrix; returns the count.
  int add_contact_blocks(const Matrix3X& x, class StiffnessAssembly& assembly) const;
  void perturb(Matrix3X& x) const;
  const System& m_system;
  std::vector<Obstacle> m_obstacles;
  double m_thickness_m;
  double m_mean_edge_m, m_shortest_edge_m;
  StaticSettings m_settings;
  Eigen::VectorXd m_contact_k;  // #V, N/m
};

}  // namespace weft::sim
