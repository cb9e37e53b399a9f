#pragma once
// Fast projection (Goldenthal et al. 2007, seed 000 §4): from the unconstrained positions x_0,
//   repeat { solve (J M⁻¹ Jᵀ) μ = C(x_j);  x_{j+1} = x_j − M⁻¹ Jᵀ μ }  (J = ∇C(x_j))
// until the largest edge strain is at most the tolerance. The paper's h² factor scales μ only
// and is dropped. Each iterate is the smallest mass-weighted step onto the linearised
// constraints, so convergence is quadratic near the solution.
//
// The matrix J M⁻¹ Jᵀ (#constraints square) has a fixed sparsity pattern — edges sharing a
// free vertex — analysed once; each iteration refills its values in place. It is solved by
// conjugate gradients preconditioned by the last factorization — an earlier iterate's or an
// earlier step's matrix, which differs little — to a relative residual (max norm, as the
// strain) proportional to the current strain (an inexact Newton method with a forcing term that
// keeps the order quadratic, Dembo, Eisenstat & Steihaug 1982), relaxed near the tolerance to
// what lands the step below half of it; when that takes more than `reuse_iterations`
// iterations the matrix is refactorized and solved directly.
// Robustness: a full step that does not halve Σ C² is shortened to the exact minimiser of Σ C²
// along it (C is quadratic, so that is a quartic in the step length: no extra factorization);
// a factorization that fails (redundant constraints make the matrix singular) is retried with
// a small diagonal shift (and is then not reused); when the cap is reached or no step reduces Σ C², the best iterate
// (smallest max strain) is kept and the result says it did not converge. Near a singular root
// — a nearly flat sheet, a chain pulled taut between pins at its rest length — Newton-type
// steps lose their quadratic convergence; the simulator avoids starting there by carrying the
// constraint forces into the next prediction (carried_tension.h, multipliers()).

#include <memory>
#include <vector>

#include "sim/constraints/projection.h"

namespace weft::sim {

class FastProjection final : public ConstraintProjector {
 public:
  FastProjection(std::vector<EdgeConstraint> constraints, Eigen::VectorXd inv_mass,
                 const ProjectionSettings& settings, SparseBackend backend);
  ~FastProjection() override;

  ProjectionResult project(Matrix3X& x) override;
  const std::vector<EdgeConstraint>& constraints() const override { return m_constraints; }
  const Eigen::VectorXd& multipliers() const override { return m_multipliers; }
  // A constraint between two held vertices keeps its row of the pattern with a constant
  // diagonal and a zero right-hand side (its multiplier is 0) and is left out of the strain.
  void set_inverse_masses(const Eigen::VectorXd& inv_mass, bool fresh) override;
  // The reusable factorization is saved as the matrix it factorizes and refactorized on
  // restore (the same bits: the factorization is deterministic).
  void save_state(StateWriter& out) const override;
  void restore_state(StateReader& in) override;

 private:
  // One entry of the lower triangle of J M⁻¹ Jᵀ: value += coefficient · d_e·d_f.
  struct Contribution {
    int slot;  // index into the matrix's value array
    int e, f;
    Index vertex;  // v, the vertex e and f share
    double sign;   // sign_e · sign_f
    double coefficient;  // sign_e · sign_f · (1/m_v) · 4 / (l_e l_f)
  };

  void build_pattern();
  double evaluate(const Matrix3X& x);  // fills m_d, m_c; returns Σ C²
  void fill_matrix();
  bool factorize_with_fallback();
  // μ with ‖A μ − C‖∞ ≤ forcing ‖C‖∞ (A = J M⁻¹ Jᵀ, filled): by the reused factorization or a new
  // one (counted in `result`). False when A cannot be factorized or μ is not finite.
  bool solve_newton_system(double forcing, Eigen::VectorXd& mu, ProjectionResult& result);
  // Conjugate gradients on A μ = C preconditioned by the last factorization, from μ = 0; false
  // when `forcing` is not reached within the allowed iterations.
  bool reuse_factorization(double forcing, Eigen::VectorXd& mu, ProjectionResult& result);
  double line_search(const Matrix3X& step, double merit) const;  // α, or 0 if none helps

  std::vector<EdgeConstraint> m_constraints;
  Eigen::VectorXd m_inv_mass;
  Eigen::VectorXd m_inv_mass_made;  // at construction, which set the pattern
  // Per constraint: whether an end is free (set_inverse_masses); the diagonal a constraint
  // between two held vertices keeps, 4 (1/m_a + 1/m_b) with the masses at construction.
  std::vector<char> m_active;
  std::vector<double> m_held_diagonal;
  bool m_any_inactive = false;
  ProjectionSettings m_settings;
  SparseMatrix m_matrix;  // lower triangle of J M⁻¹ Jᵀ
  std::vector<Contribution> m_contributions;
  std::vector<int> m_diagonal_slots;
  std::unique_ptr<SparseSpdSolver> m_solver;
  // m_solver holds a factorization of an earlier matrix that needed no diagonal shift: a
  // preconditioner for conjugate gradients. After a shift the matrix is (nearly) singular —
  // redundant constraints — and each iteration factorizes afresh.
  bool m_reusable = false;
  std::vector<double> m_factored_values;  // m_matrix's values m_solver factorized, when reusable
  Matrix3X m_d;          // #C×3 edge vectors x_b − x_a at the current iterate
  Eigen::VectorXd m_c;   // #C constraint values
  Eigen::VectorXd m_multipliers;  // #C Σ α μ of the last project(), kg·m (x moved by −M⁻¹Jᵀ Σαμ)
};

}  // namespace weft::sim
