#include "sim/constraints/fast_projection.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sim/constraints/inextensibility.h"

namespace weft::sim {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Index of (row, col) in a compressed column-major matrix's value array.
int slot_of(const SparseMatrix& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return static_cast<int>(it - m.innerIndexPtr());
}

}  // namespace

FastProjection::FastProjection(std::vector<EdgeConstraint> constraints, Eigen::VectorXd inv_mass,
                               const ProjectionSettings& settings, SparseBackend backend)
    : m_constraints(std::move(constraints)), m_inv_mass(std::move(inv_mass)), m_settings(settings) {
  m_d.resize(static_cast<Eigen::Index>(m_constraints.size()), 3);
  m_c.resize(static_cast<Eigen::Index>(m_constraints.size()));
  build_pattern();
  m_solver = make_sparse_spd_solver(backend);
  if (!m_constraints.empty()) m_solver->analyze(m_matrix);
}

FastProjection::~FastProjection() = default;

void FastProjection::build_pattern() {
  const auto n_c = static_cast<int>(m_constraints.size());
  // Constraints at each free vertex, with the sign of ∇_v C (+ at b, − at a).
  std::vector<std::vector<std::pair<int, double>>> incident(static_cast<std::size_t>(m_inv_mass.size()));
  for (int e = 0; e < n_c; ++e) {
    const EdgeConstraint& c = m_constraints[static_cast<std::size_t>(e)];
    if (m_inv_mass[c.a] > 0.0) incident[static_cast<std::size_t>(c.a)].push_back({e, -1.0});
    if (m_inv_mass[c.b] > 0.0) incident[static_cast<std::size_t>(c.b)].push_back({e, +1.0});
  }
  struct Pending { int row, col; double coefficient; };
  std::vector<Pending> pending;
  std::vector<Eigen::Triplet<double, int>> triplets;
  for (int e = 0; e < n_c; ++e) triplets.emplace_back(e, e, 0.0);  // diagonal always present
  for (std::size_t v = 0; v < incident.size(); ++v) {
    for (const auto& [e, se] : incident[v]) {
      for (const auto& [f, sf] : incident[v]) {
        if (f > e) continue;  // lower triangle: row e ≥ column f
        const double le = m_constraints[static_cast<std::size_t>(e)].rest_m;
        const double lf = m_constraints[static_cast<std::size_t>(f)].rest_m;
        pending.push_back({e, f, se * sf * m_inv_mass[static_cast<Eigen::Index>(v)] * 4.0 / (le * lf)});
        triplets.emplace_back(e, f, 0.0);
      }
    }
  }
  m_matrix.resize(n_c, n_c);
  m_matrix.setFromTriplets(triplets.begin(), triplets.end());
  m_matrix.makeCompressed();
  m_contributions.reserve(pending.size());
  for (const Pending& p : pending)
    m_contributions.push_back({slot_of(m_matrix, p.row, p.col), p.row, p.col, p.coefficient});
  m_diagonal_slots.resize(static_cast<std::size_t>(n_c));
  for (int e = 0; e < n_c; ++e) m_diagonal_slots[static_cast<std::size_t>(e)] = slot_of(m_matrix, e, e);
}

double FastProjection::evaluate(const Matrix3X& x) {
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < m_constraints.size(); ++k) {
    const EdgeConstraint& c = m_constraints[k];
    const auto e = static_cast<Eigen::Index>(k);
    m_d.row(e) = x.row(c.b) - x.row(c.a);
    m_c[e] = m_d.row(e).squaredNorm() / c.rest_m - c.rest_m;
    sum_sq += m_c[e] * m_c[e];
  }
  return sum_sq;
}

void FastProjection::fill_matrix() {
  double* values = m_matrix.valuePtr();
  std::fill(values, values + m_matrix.nonZeros(), 0.0);
  for (const Contribution& t : m_contributions)
    values[t.slot] += t.coefficient * m_d.row(t.e).dot(m_d.row(t.f));
}

// Redundant constraints (e.g. closed loops of pinned neighbours) or a perfectly degenerate
// configuration make J M⁻¹ Jᵀ singular; a diagonal shift of 1e-10, then 1e-6, of its mean
// diagonal regularises it (a tiny compliance) without changing the pattern.
bool FastProjection::factorize_with_fallback() {
  if (m_solver->factorize(m_matrix)) return true;
  double mean_diagonal = 0.0;
  for (int s : m_diagonal_slots) mean_diagonal += m_matrix.valuePtr()[s];
  mean_diagonal /= static_cast<double>(std::max<std::size_t>(1, m_diagonal_slots.size()));
  double applied = 0.0;
  for (double relative : {1e-10, 1e-6}) {
    const double shift = relative * mean_diagonal - applied;
    for (int s : m_diagonal_slots) m_matrix.valuePtr()[s] += shift;
    applied += shift;
    if (m_solver->factorize(m_matrix)) return true;
  }
  return false;
}

ProjectionResult FastProjection::project(Matrix3X& x) {
  ProjectionResult result;
  if (m_constraints.empty()) return result;
  double merit = evaluate(x);
  result.max_strain = max_edge_strain(m_constraints, x);
  Matrix3X best = x;
  double best_strain = result.max_strain;
  Matrix3X trial(x.rows(), 3);
  Matrix3X step(x.rows(), 3);
  double lambda = 0.0;  // Levenberg–Marquardt damping, relative to the diagonal

  while (result.max_strain > m_settings.tolerance && result.iterations < m_settings.max_iterations) {
    ++result.iterations;
    bool accepted = false;
    for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
      const auto start = Clock::now();
      fill_matrix();
      for (int s : m_diagonal_slots) m_matrix.valuePtr()[s] *= 1.0 + lambda;
      const bool factorized = factorize_with_fallback();
      Eigen::VectorXd mu;
      if (factorized) mu = m_solver->solve(m_c);
      result.solve_s += seconds_since(start);
      if (!factorized || !mu.allFinite()) break;

      // δx = −M⁻¹ Jᵀ μ, with ∇_b C = 2 d / l = −∇_a C.
      step.setZero();
      for (std::size_t k = 0; k < m_constraints.size(); ++k) {
        const EdgeConstraint& c = m_constraints[k];
        const auto e = static_cast<Eigen::Index>(k);
        const Eigen::RowVector3d g = (2.0 * mu[e] / c.rest_m) * m_d.row(e);
        step.row(c.b) -= m_inv_mass[c.b] * g;
        step.row(c.a) += m_inv_mass[c.a] * g;
      }
      trial = x + step;
      const double trial_merit = evaluate(trial);
      if (trial_merit < merit) {
        accepted = true;
        x.swap(trial);
        merit = trial_merit;
        lambda = lambda > 1e-9 ? 0.1 * lambda : 0.0;
      } else {
        evaluate(x);  // back to the current iterate's d and C
        lambda = lambda > 0.0 ? 10.0 * lambda : 1e-4;
      }
    }
    if (!accepted) break;  // stalled: no damping gives a decrease
    result.max_strain = max_edge_strain(m_constraints, x);
    if (result.max_strain < best_strain) {
      best_strain = result.max_strain;
      best = x;
    }
  }
  result.converged = result.max_strain <= m_settings.tolerance;
  if (!result.converged && best_strain < result.max_strain) {
    x = best;
    result.max_strain = best_strain;
  }
  return result;
}

}  // namespace weft::sim
