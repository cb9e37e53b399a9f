// Fast projection with self-contacts; the method is stated in contact_projection.h.

#include "sim/constraints/contact_projection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "base/timer.h"

namespace weft::sim {
namespace {

// Per vertex, the rows (edges first, then active contacts) acting on it with their gradients.
using ContactIncidentRows = std::vector<std::vector<std::pair<int, Vec3>>>;

// The contact rows inside at x (violation < 0), by index into rows.
void find_active_contact_rows(const Matrix3X& x, const std::vector<SelfContactRow>& rows,
                              double distance_m, double lateral_m, std::vector<int>& active_ids) {
  active_ids.clear();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (rows[k].violation(x, distance_m, lateral_m) < 0.0) active_ids.push_back(static_cast<int>(k));
  }
}

// The constraints linearised at x: their values (rhs: the edges, then the active contact rows)
// and, per free vertex, the gradients of the rows acting on it.
void linearise_edges_and_contacts(const std::vector<EdgeConstraint>& edges,
                                  const std::vector<SelfContactRow>& rows,
                                  const std::vector<int>& active_ids, const Matrix3X& x,
                                  const Eigen::VectorXd& inv_mass, double distance_m,
                                  Eigen::VectorXd& rhs, ContactIncidentRows& incident) {
  const auto n_e = static_cast<int>(edges.size());
  for (auto& list : incident) list.clear();
  for (int e = 0; e < n_e; ++e) {
    const EdgeConstraint& c = edges[static_cast<std::size_t>(e)];
    const Vec3 d = (x.row(c.b) - x.row(c.a)).transpose();
    rhs[e] = d.squaredNorm() / c.rest_m - c.rest_m;
    const Vec3 g = (2.0 / c.rest_m) * d;
    if (inv_mass[c.a] > 0.0) incident[static_cast<std::size_t>(c.a)].push_back({e, -g});
    if (inv_mass[c.b] > 0.0) incident[static_cast<std::size_t>(c.b)].push_back({e, g});
  }
  for (std::size_t i = 0; i < active_ids.size(); ++i) {
    const SelfContactRow& r = rows[static_cast<std::size_t>(active_ids[i])];
    const int id = n_e + static_cast<int>(i);
    rhs[id] = r.gap(x) - distance_m;
    for (std::size_t k = 0; k < 4; ++k)
      if (inv_mass[r.v[k]] > 0.0 && r.w[k] != 0.0)
        incident[static_cast<std::size_t>(r.v[k])].push_back({id, r.w[k] * r.n});
  }
}

// A = J M⁻¹ Jᵀ (n × n, lower triangle) from the gradients; returns the mean of its diagonal.
double assemble_contact_system(const ContactIncidentRows& incident,
                               const Eigen::VectorXd& inv_mass, int n,
                               std::vector<Eigen::Triplet<double, int>>& triplets,
                               SparseMatrix& A) {
  triplets.clear();
  for (std::size_t v = 0; v < incident.size(); ++v) {
    const double m = inv_mass[static_cast<Eigen::Index>(v)];
    for (const auto& [i, gi] : incident[v])
      for (const auto& [j, gj] : incident[v])
        if (j <= i) triplets.emplace_back(i, j, m * gi.dot(gj));
  }
  for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, 0.0);
  A.setFromTriplets(triplets.begin(), triplets.end());
  A.makeCompressed();
  double mean_diagonal = 0.0;
  for (int i = 0; i < n; ++i) mean_diagonal += A.coeff(i, i);
  mean_diagonal /= std::max(1, n);
  // A row no free vertex takes part in (an edge between vertices held as a taut chain) moves
  // nothing: a unit diagonal keeps the matrix definite.
  for (int i = 0; i < n; ++i)
    if (!(A.coeff(i, i) > 0.0)) A.coeffRef(i, i) = mean_diagonal > 0.0 ? mean_diagonal : 1.0;
  return mean_diagonal;
}

// Factorizes A (analysed) with a compliance on the contact rows (rows n_e and on) of 1e-8 of
// the mean diagonal, then 1e-6 and 1e-4 of it on every row, until a factorization succeeds.
// Counts the attempts in factorizations; false when none succeeded.
bool factorize_with_contact_compliance(SparseSpdSolver& solver, SparseMatrix& A, int n_e,
                                       double mean_diagonal, int& factorizations) {
  const auto n = static_cast<int>(A.rows());
  double applied = 0.0;
  for (double relative : {1e-8, 1e-6, 1e-4}) {
    const double shift = relative * mean_diagonal - applied;
    for (int i = n_e; i < n; ++i) A.coeffRef(i, i) += shift;
    if (relative > 1e-8)  // the edges too, once the compliance of the contacts did not do
      for (int i = 0; i < n_e; ++i) A.coeffRef(i, i) += shift;
    applied += shift;
    ++factorizations;
    if (solver.factorize(A)) return true;
  }
  return false;
}

// The full step −M⁻¹ Jᵀ μ.
void contact_projection_step(const ContactIncidentRows& incident, const Eigen::VectorXd& inv_mass,
                             const Eigen::VectorXd& mu, Matrix3X& step) {
  step.setZero();
  for (std::size_t v = 0; v < incident.size(); ++v) {
    const double m = inv_mass[static_cast<Eigen::Index>(v)];
    for (const auto& [i, g] : incident[v]) step.row(static_cast<Eigen::Index>(v)) -= (m * mu[i]) * g.transpose();
  }
}

// The step length α, halved from 1 (at most 20 times) until the merit at x + α step is below
// current, and that merit; a merit not below current after the last halving means stalled.
template <class MeritAt>
std::pair<double, double> halve_until_merit_decreases(const Matrix3X& x, const Matrix3X& step,
                                                      double current, const MeritAt& merit_at) {
  double alpha = 1.0;
  double next = merit_at(x + step);
  for (int halvings = 0; halvings < 20 && !(next < current); ++halvings) {
    alpha *= 0.5;
    next = merit_at(x + alpha * step);
  }
  return {alpha, next};
}

}  // namespace

ContactProjection::ContactProjection(std::vector<EdgeConstraint> edges, double tolerance,
                                     int max_iterations, SparseBackend backend)
    : m_edges(std::move(edges)),
      m_tolerance(tolerance),
      m_max_iterations(max_iterations),
      m_solver(make_sparse_spd_solver(backend)) {}

ContactProjection::~ContactProjection() = default;

double ContactProjection::merit(const Matrix3X& x, const std::vector<SelfContactRow>& rows,
                                double distance_m, double lateral_m) const {
  double sum = 0.0;
  for (const EdgeConstraint& c : m_edges) {
    const double value = (x.row(c.b) - x.row(c.a)).squaredNorm() / c.rest_m - c.rest_m;
    sum += value * value;
  }
  for (const SelfContactRow& r : rows) {
    const double value = r.violation(x, distance_m, lateral_m);
    sum += value * value;
  }
  return sum;
}

ContactProjectionResult ContactProjection::project(Matrix3X& x, const Eigen::VectorXd& inv_mass,
                                                   const std::vector<SelfContactRow>& rows,
                                                   double distance_m, double lateral_m) {
  ContactProjectionResult out;
  ProjectionResult& result = out.projection;
  const auto n_e = static_cast<int>(m_edges.size());
  m_multipliers.setZero(n_e);
  const double band_m = contact_tolerance * distance_m;
  const auto worst_row = [&](const Matrix3X& at) {
    double worst = 0.0;
    for (const SelfContactRow& r : rows) worst = std::min(worst, r.violation(at, distance_m, lateral_m));
    return worst;
  };
  const auto done = [&](double strain, double worst) {
    return strain <= m_tolerance && worst >= -band_m;
  };
  result.max_strain = max_edge_strain(m_edges, x);
  double worst = worst_row(x);
  double current = merit(x, rows, distance_m, lateral_m);
  Matrix3X best = x;
  Eigen::VectorXd best_multipliers = m_multipliers;
  double best_merit = current;

  ContactIncidentRows incident(static_cast<std::size_t>(x.rows()));
  std::vector<int> active_ids;
  std::vector<Eigen::Triplet<double, int>> triplets;
  Matrix3X step(x.rows(), 3);
  while (!done(result.max_strain, worst) && result.iterations < m_max_iterations) {
    ++result.iterations;
    const base::Stopwatch watch;
    find_active_contact_rows(x, rows, distance_m, lateral_m, active_ids);
    out.active_rows = std::max(out.active_rows, static_cast<int>(active_ids.size()));
    const int n = n_e + static_cast<int>(active_ids.size());
    Eigen::VectorXd rhs(n);
    linearise_edges_and_contacts(m_edges, rows, active_ids, x, inv_mass, distance_m, rhs, incident);
    SparseMatrix A(n, n);
    const double mean_diagonal = assemble_contact_system(incident, inv_mass, n, triplets, A);
    m_solver->analyze(A);
    if (!factorize_with_contact_compliance(*m_solver, A, n_e, mean_diagonal,
                                           result.factorizations)) {
      result.solve_s += watch.seconds();
      break;
    }
    const Eigen::VectorXd mu = m_solver->solve(rhs);
    result.solve_s += watch.seconds();
    if (!mu.allFinite()) break;
    contact_projection_step(incident, inv_mass, mu, step);
    const auto merit_at = [&](const Matrix3X& at) {
      return merit(at, rows, distance_m, lateral_m);
    };
    const auto [alpha, next] = halve_until_merit_decreases(x, step, current, merit_at);
    if (!(next < current)) break;  // stalled
    x += alpha * step;
    m_multipliers += alpha * mu.head(n_e);
    current = next;
    result.max_strain = max_edge_strain(m_edges, x);
    worst = worst_row(x);
    if (current < best_merit) {
      best_merit = current;
      best = x;
      best_multipliers = m_multipliers;
    }
  }
  result.converged = done(result.max_strain, worst);
  if (!result.converged && best_merit < current) {
    x = best;
    m_multipliers = best_multipliers;
    result.max_strain = max_edge_strain(m_edges, x);
    worst = worst_row(x);
  }
  out.worst_gap_m = worst + distance_m;
  return out;
}

}  // namespace weft::sim
