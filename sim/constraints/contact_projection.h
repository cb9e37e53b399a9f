#pragma once
// Fast projection with self-contacts: the inextensibility constraints of fast
// projection (fast_projection.h) and the step's self-contact rows (sim/collision/
// self_contact_rows.h) projected together, so that the projection — which runs last in a step —
// cannot push one layer of cloth through another.
//
// The constraints: C_e(x) = |x_b − x_a|² / l − l = 0 per edge, and c_k(x) = g_k(x) − distance ≥ 0
// per contact row (g linear in x). Newton on the active set: each iterate solves
//   (J M⁻¹ Jᵀ) μ = (C, c_active),   x ← x − α M⁻¹ Jᵀ μ
// with J the gradients of the edges and of the active rows — those inside, c_k < 0, whose two
// material points are still near each other (SelfContactRow::violation: a pair that slid
// apart by more than lateral_m is no contact any more). Each iterate is the smallest
// mass-weighted step onto the linearised constraints; the contact rows are linear, so they
// hold exactly after a full step. The pattern changes with the active set, so each iterate
// analyses and factorizes afresh. Contact rows may be redundant (a vertex–triangle and an
// edge–edge row for one touch), so the rows of the contacts carry a compliance of 1e-8 of the
// mean diagonal (more, 1e-6 then 1e-4, if the factorization fails). α halves from 1 until the
// merit Σ C_e² + Σ_k violation_k² decreases.
// Converged: the largest edge strain is at most the tolerance and no row is more than a
// quarter of the distance inside (c_k ≥ −distance/4), which keeps each pair on its side.
// Otherwise, at the iteration cap or when no step decreases the merit, the best iterate (by
// merit) is kept.

#include <memory>
#include <vector>

#include "sim/collision/self_contact_rows.h"
#include "sim/constraints/projection.h"
#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim {

struct ContactProjectionResult {
  ProjectionResult projection;  // iterations, factorizations, strain, convergence
  int active_rows = 0;          // the most rows active in one iterate
  double worst_gap_m = 0.0;     // the smallest c_k + distance over the rows at the end
};

class ContactProjection {
 public:
  ContactProjection(std::vector<EdgeConstraint> edges, double tolerance, int max_iterations,
                    SparseBackend backend);
  ~ContactProjection();

  // Moves x (#V×3, m) onto the edges and the rows (distance_m the contact distance), changing
  // only vertices with inv_mass (#V) > 0.
  ContactProjectionResult project(Matrix3X& x, const Eigen::VectorXd& inv_mass,
                                  const std::vector<SelfContactRow>& rows, double distance_m,
                                  double lateral_m);
  // Per edge, Σ α μ of the last project() (kg·m), as ConstraintProjector::multipliers().
  const Eigen::VectorXd& multipliers() const { return m_multipliers; }

  // Rows inside by more than this fraction of the distance are not converged.
  static constexpr double contact_tolerance = 0.25;

 private:
  double merit(const Matrix3X& x, const std::vector<SelfContactRow>& rows, double distance_m,
               double lateral_m) const;

  std::vector<EdgeConstraint> m_edges;
  double m_tolerance;
  int m_max_iterations;
  std::unique_ptr<SparseSpdSolver> m_solver;
  Eigen::VectorXd m_multipliers;
};

}  // namespace weft::sim
