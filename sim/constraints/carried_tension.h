#pragma once
// Constraint forces carried from one step to the next.
//
// Fast projection corrects the unconstrained prediction x̃ by −M⁻¹ Jᵀ μ: over a step of h
// seconds that is the constraint force f = −Jᵀ μ / h², along each constrained edge
// f_b = −(2 μ / (l h²)) (x_b − x_a) = −f_a, since ∇_b C = 2 (x_b − x_a) / l. A hanging cloth
// needs that force every step; leaving it out of the prediction lets gravity pull the cloth
// off the constraints each step and projection pull it back — from a nearly flat sheet or a
// chain pulled taut between pins, a correction along directions where C is only quadratic
// (a singular root), which Newton-type iterations cannot finish in a few iterations.
// Carrying the tension k = Σ 2 μ / (l h²) (N/m per edge, the stiffness of a zero-rest-length
// spring) into the next prediction, with its stiffness k I in the implicit matrix (the string
// stiffness of a taut thread), leaves projection only the change of tension to find.

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/constraints/projection.h"
#include "sim/force_term.h"
#include "sim/types.h"

namespace weft::sim {

// forces (#V×3, N) += the tension forces of k (#edges, N/m) at positions x. An empty k adds none.
void add_tension_forces(const std::vector<EdgeConstraint>& edges, const Eigen::VectorXd& k,
                        const Matrix3X& x, Matrix3X& forces);

// k += 2 μ / (l h²): the tension implied by a projection's multipliers μ (kg·m) over h seconds.
void accumulate_tension(const std::vector<EdgeConstraint>& edges, const Eigen::VectorXd& mu,
                        double h_s, Eigen::VectorXd& k);

// The carried tension as a force term of a System: a zero-rest-length spring of stiffness k_e
// on each constrained edge, k_e ≥ 0 from the projections so far (none before the first). Its
// stiffness for implicit Euler is max(0, k_e) I (compression would make the matrix
// indefinite: its force is kept, its stiffness dropped). The force is a constraint force
// carried over, not an elastic one: energy() is 0, so the diagnostics' elastic energy counts
// only the cloth's own terms.
class CarriedTensionTerm final : public PairForceTerm {
 public:
  explicit CarriedTensionTerm(std::vector<EdgeConstraint> edges) : m_edges(std::move(edges)) {}
  // k += 2 μ / (l h²) from a projection's multipliers μ over h seconds.
  void accumulate(const Eigen::VectorXd& mu, double h_s) { accumulate_tension(m_edges, mu, h_s, m_k); }
  const Eigen::VectorXd& tension_N_m() const { return m_k; }  // #edges, or empty before any
  // For a checkpoint: the tension so far (#edges, or empty before any).
  void restore_tension(const Eigen::VectorXd& k) {
    if (k.size() != 0 && k.size() != static_cast<Eigen::Index>(m_edges.size()))
      throw std::invalid_argument("carried tension: " + std::to_string(k.size()) +
                                  " values for " + std::to_string(m_edges.size()) + " edges");
    m_k = k;
  }

  std::string describe() const override {
    return "carried constraint tension on " + std::to_string(m_edges.size()) + " edges";
  }
  std::size_t element_count() const override { return m_edges.size(); }
  std::pair<Index, Index> pair(std::size_t e) const override { return {m_edges[e].a, m_edges[e].b}; }
  Mat3 pair_stiffness(const Matrix3X&, std::size_t e, bool) const override {
    const double k = m_k.size() > 0 ? m_k[static_cast<Eigen::Index>(e)] : 0.0;
    return std::max(0.0, k) * Mat3::Identity();
  }
  double energy(const Matrix3X&) const override { return 0.0; }
  void add_forces(const Matrix3X& x, Matrix3X& f) const override {
    add_tension_forces(m_edges, m_k, x, f);
  }
  void add_stiffness_row_bound(Eigen::VectorXd& bound) const override {
    for (std::size_t e = 0; e < m_edges.size() && m_k.size() > 0; ++e) {
      const double k = std::max(0.0, m_k[static_cast<Eigen::Index>(e)]);
      bound[m_edges[e].a] += 2.0 * k;
      bound[m_edges[e].b] += 2.0 * k;
    }
  }

 private:
  std::vector<EdgeConstraint> m_edges;
  Eigen::VectorXd m_k;  // N/m per edge
};

}  // namespace weft::sim
