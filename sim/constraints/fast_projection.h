#pragma once
// Fast projection (Goldenthal et al. 2007, seed 000 §4): from the unconstrained positions x_0,
//   repeat { solve (J M⁻¹ Jᵀ) μ = C(x_j);  x_{j+1} = x_j − M⁻¹ Jᵀ μ }  (J = ∇C(x_j))
// until the largest edge strain is at most the tolerance. The paper's h² factor scales μ only
// and is dropped. Each iterate is the smallest mass-weighted step onto the linearised
// constraints, so convergence is quadratic near the solution.
//
// The matrix J M⁻¹ Jᵀ (#constraints square) has a fixed sparsity pattern — edges sharing a
// free vertex — analysed once; each iteration refills its values in place and refactorizes.
// Robustness: a step that does not reduce ½‖C‖² is retried with Levenberg–Marquardt damping
// (J M⁻¹ Jᵀ's diagonal scaled by 1 + λ, λ growing tenfold from 1e-4 and shrinking again after
// a success): near a singular root — an edge chain pulled taut between two pins at exactly its
// rest length, where J loses rank — undamped steps overshoot and stall; a factorization
// that fails (redundant constraints make the matrix singular) is retried with a small diagonal
// shift; when the cap is reached, the best iterate (smallest max strain) is kept and the result
// says it did not converge.

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

 private:
  // One entry of the lower triangle of J M⁻¹ Jᵀ: value += coefficient · d_e·d_f.
  struct Contribution {
    int slot;  // index into the matrix's value array
    int e, f;
    double coefficient;  // sign_e · sign_f · (1/m_v) · 4 / (l_e l_f)
  };

  void build_pattern();
  double evaluate(const Matrix3X& x);  // fills m_d, m_c; returns Σ C²
  void fill_matrix();
  bool factorize_with_fallback();

  std::vector<EdgeConstraint> m_constraints;
  Eigen::VectorXd m_inv_mass;
  ProjectionSettings m_settings;
  SparseMatrix m_matrix;  // lower triangle of J M⁻¹ Jᵀ
  std::vector<Contribution> m_contributions;
  std::vector<int> m_diagonal_slots;
  std::unique_ptr<SparseSpdSolver> m_solver;
  Matrix3X m_d;          // #C×3 edge vectors x_b − x_a at the current iterate
  Eigen::VectorXd m_c;   // #C constraint values
};

}  // namespace weft::sim
