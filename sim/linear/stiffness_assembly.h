#pragma once
// The sparse 3#V×3#V matrix  A = diag(d ⊗ I₃) + s K  of a System's force terms, with
// K = Σ_pairs [H −H; −H H] + Σ_elements K_e their (PSD-projected) stiffness — what implicit
// Euler solves (d = M (1 + h α), s = h²) and what the static equilibrium solver's Newton steps
// solve (d = a Levenberg–Marquardt shift μ M, s = 1). Degree of freedom 3i + c is coordinate c
// of vertex i, the row-major #V×3 matrices' order.
//
// A is kept as its lower triangle (SparseSpdSolver's contract). Its pattern depends only on the
// terms' elements and the pins, so it is built once; each fill() writes the values through
// `slots` — one entry of the compressed matrix's valuePtr per contribution, in the fixed order
// of the pattern's loops — so refilling is one linear pass, without triplets or sorting, and
// gives the same bits every time. A pinned vertex's rows and columns are the identity (its DOFs
// are eliminated; nothing couples it to the free vertices). Every free vertex's 3×3 diagonal
// block is in the pattern, so diagonal_block() can add to it (resting contacts, barriers).

#include <cstddef>
#include <vector>

#include "sim/force_term.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/system.h"
#include "sim/types.h"

namespace weft::sim {

class StiffnessAssembly {
 public:
  // What a matrix takes in: every term with stiffness (a static solve), or only those whose
  // stiffness belongs in a time step (ForceTerm::stiffness_in_time_step: implicit Euler).
  enum class Terms { all, time_step };
  // The pattern of `system`'s terms with stiffness and pins (inv_mass 0). Terms naming
  // vertices out of range, or a pair joining a vertex to itself, are bugs (WEFT_CHECK,
  // base::InternalError), named by the term's description and `who`.
  StiffnessAssembly(const System& system, Terms terms, const char* who);

  // A = diag(d) + s K(x) on the free DOFs (d: #V, per vertex, kg or N/m as the caller means),
  // identity on the pinned ones. With kv non-null, also kv = K(x) v (#V×3; every pair, so that
  // a moving pin is seen by its neighbours). project_psd false: each element's exact Hessian,
  // which may make A indefinite (a static solve near a stable equilibrium uses it). A time
  // step's matrix (Terms::time_step, project_psd) takes each element's time_step_stiffness.
  void fill(const Matrix3X& x, const Eigen::VectorXd& d, double s, const Matrix3X* v = nullptr,
            Matrix3X* kv = nullptr, bool project_psd = true);

  // The stored (lower-triangle) entry at (row, col), row ≥ col; not in the pattern: a bug.
  double& lower_entry(int row, int col);
  // Adds the symmetric block B to vertex i's diagonal block (i free).
  void add_diagonal_block(Index i, const Mat3& B);

  const SparseMatrix& matrix() const { return m_A; }
  bool pinned(Index i) const { return m_pinned[static_cast<std::size_t>(i)] != 0; }
  // WEFT_CHECKs that `system` still has the terms and vertex count this was built for.
  void check_structure(const System& system, const char* who) const;

 private:
  void sort_terms(const System& system, Terms terms, const char* who);
  void build_pattern();
  std::size_t add_pair(Index a, Index b, const Mat3& H, double s, const Matrix3X* v,
                       Matrix3X* kv, std::size_t k);
  std::size_t add_element(const Index* vertices, int size, const ElementMatrix& K, double s,
                          const Matrix3X* v, Matrix3X* kv, std::size_t k);

  bool m_time_step;  // Terms::time_step: elements enter by ForceTerm::time_step_stiffness
  std::vector<char> m_pinned;  // #V, inv_mass == 0
  // Pair terms first, then the other terms with stiffness: the order of the pattern and fill.
  std::vector<const PairForceTerm*> m_pair_terms;
  std::vector<const ForceTerm*> m_element_terms;
  std::vector<std::size_t> m_element_counts;  // of every term of the system
  SparseMatrix m_A;                           // lower triangle
  std::vector<int> m_slots;  // valuePtr index of each contribution, in assembly order
};

}  // namespace weft::sim
