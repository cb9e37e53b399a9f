#include "sim/constraints/fast_projection.h"

#include <algorithm>
#include <cmath>

#include "base/timer.h"
#include "sim/constraints/inextensibility.h"

namespace weft::sim {
namespace {

// Index of (row, col) in a compressed column-major matrix's value array.
int slot_of(const SparseMatrix& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return static_cast<int>(it - m.innerIndexPtr());
}

// The Newton system is solved to a residual of forcing × ‖C‖∞, and the step then leaves a
// strain of about forcing × ε (plus ε², the constraints' curvature). 0.1 ε keeps the quadratic
// order (an inexact Newton method whose forcing term shrinks with the error); near the
// tolerance only tol/2 is needed, so the forcing term is relaxed to tol/(2ε), at most 1/2:
// fewer conjugate-gradient iterations on a reused factorization, and fewer refactorizations.
double projection_forcing_term(double strain, double tolerance) {
  if (!(strain > 0.0)) return 0.1;
  const double quadratic = 0.1 * std::min(1.0, strain);
  return std::min(0.5, std::max(quadratic, 0.5 * tolerance / strain));
}

}  // namespace

FastProjection::FastProjection(std::vector<EdgeConstraint> constraints, Eigen::VectorXd inv_mass,
                               const ProjectionSettings& settings, SparseBackend backend)
    : m_constraints(std::move(constraints)),
      m_inv_mass(std::move(inv_mass)),
      m_inv_mass_made(m_inv_mass),
      m_active(m_constraints.size(), 1),
      m_settings(settings) {
  m_held_diagonal.reserve(m_constraints.size());
  for (const EdgeConstraint& c : m_constraints)
    m_held_diagonal.push_back(4.0 * (m_inv_mass[c.a] + m_inv_mass[c.b]));
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
  struct Pending { int row, col; Index vertex; double sign, coefficient; };
  std::vector<Pending> pending;
  std::vector<Eigen::Triplet<double, int>> triplets;
  for (int e = 0; e < n_c; ++e) triplets.emplace_back(e, e, 0.0);  // diagonal always present
  for (std::size_t v = 0; v < incident.size(); ++v) {
    for (const auto& [e, se] : incident[v]) {
      for (const auto& [f, sf] : incident[v]) {
        if (f > e) continue;  // lower triangle: row e ≥ column f
        const double le = m_constraints[static_cast<std::size_t>(e)].rest_m;
        const double lf = m_constraints[static_cast<std::size_t>(f)].rest_m;
        pending.push_back({e, f, static_cast<Index>(v), se * sf,
                           se * sf * m_inv_mass[static_cast<Eigen::Index>(v)] * 4.0 / (le * lf)});
        triplets.emplace_back(e, f, 0.0);
      }
    }
  }
  m_matrix.resize(n_c, n_c);
  m_matrix.setFromTriplets(triplets.begin(), triplets.end());
  m_matrix.makeCompressed();
  m_contributions.reserve(pending.size());
  for (const Pending& p : pending)
    m_contributions.push_back(
        {slot_of(m_matrix, p.row, p.col), p.row, p.col, p.vertex, p.sign, p.coefficient});
  m_diagonal_slots.resize(static_cast<std::size_t>(n_c));
  for (int e = 0; e < n_c; ++e) m_diagonal_slots[static_cast<std::size_t>(e)] = slot_of(m_matrix, e, e);
}

void FastProjection::set_inverse_masses(const Eigen::VectorXd& inv_mass, bool fresh) {
  require_held_kept(m_inv_mass_made, inv_mass);
  m_inv_mass = inv_mass;
  for (Contribution& t : m_contributions) {
    const double le = m_constraints[static_cast<std::size_t>(t.e)].rest_m;
    const double lf = m_constraints[static_cast<std::size_t>(t.f)].rest_m;
    t.coefficient = t.sign * m_inv_mass[t.vertex] * 4.0 / (le * lf);  // as build_pattern
  }
  m_any_inactive = false;
  for (std::size_t k = 0; k < m_constraints.size(); ++k) {
    const EdgeConstraint& c = m_constraints[k];
    m_active[k] = m_inv_mass[c.a] != 0.0 || m_inv_mass[c.b] != 0.0;
    m_any_inactive = m_any_inactive || !m_active[k];
  }
  if (fresh) {
    m_reusable = false;
    m_factored_values.clear();
  }
}

double FastProjection::evaluate(const Matrix3X& x) {
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < m_constraints.size(); ++k) {
    const EdgeConstraint& c = m_constraints[k];
    const auto e = static_cast<Eigen::Index>(k);
    m_d.row(e) = x.row(c.b) - x.row(c.a);
    m_c[e] = m_active[k] ? m_d.row(e).squaredNorm() / c.rest_m - c.rest_m : 0.0;
    sum_sq += m_c[e] * m_c[e];
  }
  return sum_sq;
}

void FastProjection::fill_matrix() {
  double* values = m_matrix.valuePtr();
  std::fill(values, values + m_matrix.nonZeros(), 0.0);
  for (const Contribution& t : m_contributions)
    values[t.slot] += t.coefficient * m_d.row(t.e).dot(m_d.row(t.f));
  if (m_any_inactive)
    for (std::size_t k = 0; k < m_constraints.size(); ++k)
      if (!m_active[k]) values[m_diagonal_slots[k]] = m_held_diagonal[k];
}

// Redundant constraints (e.g. closed loops of pinned neighbours) or a perfectly degenerate
// configuration make J M⁻¹ Jᵀ singular; a diagonal shift of 1e-10, then 1e-6, of its mean
// diagonal regularises it (a tiny compliance) without changing the pattern.
bool FastProjection::factorize_with_fallback() {
  m_reusable = m_solver->factorize(m_matrix);
  if (m_reusable) {
    if (m_settings.reuse_iterations > 0)  // for a checkpoint (save_state)
      m_factored_values.assign(m_matrix.valuePtr(), m_matrix.valuePtr() + m_matrix.nonZeros());
    return true;
  }
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

bool FastProjection::solve_newton_system(double forcing, Eigen::VectorXd& mu,
                                         ProjectionResult& result) {
  if (m_reusable && m_settings.reuse_iterations > 0 && reuse_factorization(forcing, mu, result))
    return true;
  ++result.factorizations;
  if (!factorize_with_fallback()) return false;
  mu = m_solver->solve(m_c);
  return mu.allFinite();
}

// Preconditioned conjugate gradients (A is symmetric positive definite, and so is the
// preconditioner: a Cholesky factorization of an earlier A). A first solve alone would be a
// chord step, which converges only linearly; the iterations correct it to the forcing term.
bool FastProjection::reuse_factorization(double forcing, Eigen::VectorXd& mu,
                                         ProjectionResult& result) {
  const auto A = m_matrix.selfadjointView<Eigen::Lower>();
  const double target = forcing * m_c.lpNorm<Eigen::Infinity>();  // max strain is a max norm
  mu.setZero(m_c.size());
  Eigen::VectorXd r = m_c;
  Eigen::VectorXd z = m_solver->solve(r);
  Eigen::VectorXd p = z;
  Eigen::VectorXd Ap(m_c.size());
  double rz = r.dot(z);
  for (int k = 0; k < m_settings.reuse_iterations; ++k) {
    ++result.reuse_iterations;
    Ap.noalias() = A * p;
    const double pAp = p.dot(Ap);
    if (!(pAp > 0.0) || !(rz > 0.0)) return false;
    const double step = rz / pAp;
    mu += step * p;
    r -= step * Ap;
    if (r.lpNorm<Eigen::Infinity>() <= target) return mu.allFinite();
    z = m_solver->solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

// Along the Newton direction δ the constraints are exactly quadratic,
//   C_e(x + α δ) = C_e + α L_e + α² Q_e,   L_e = ∇C_e·δ,   Q_e = |δ_b − δ_a|² / l_e,
// so Σ C_e² along the ray is a quartic in α whose coefficients one pass computes. Its
// minimiser over (0, 2] (a fine scan, then Newton on the derivative) is the step taken when the
// full step α = 1 does not halve Σ C²: a short one where the linearisation is poor (near-flat
// sheets, chains pulled taut between pins), found without another factorization.
double FastProjection::line_search(const Matrix3X& step, double merit) const {
  double a[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < m_constraints.size(); ++k) {
    const EdgeConstraint& c = m_constraints[k];
    const auto e = static_cast<Eigen::Index>(k);
    const Eigen::RowVector3d dd = step.row(c.b) - step.row(c.a);
    const double lin = 2.0 * m_d.row(e).dot(dd) / c.rest_m;
    const double quad = dd.squaredNorm() / c.rest_m;
    a[0] += m_c[e] * m_c[e];
    a[1] += 2.0 * m_c[e] * lin;
    a[2] += lin * lin + 2.0 * m_c[e] * quad;
    a[3] += 2.0 * lin * quad;
    a[4] += quad * quad;
  }
  const auto f = [&](double t) { return a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * a[4]))); };
  const auto df = [&](double t) { return a[1] + t * (2 * a[2] + t * (3 * a[3] + t * 4 * a[4])); };
  const auto d2f = [&](double t) { return 2 * a[2] + t * (6 * a[3] + t * 12 * a[4]); };
  // The full step when it at least halves Σ C² (the paper's iteration, quadratic near the
  // solution); otherwise the best step along the ray.
  if (f(1.0) <= 0.5 * merit) return 1.0;
  double best = 1.0;
  for (int i = 1; i <= 64; ++i) {
    const double t = i / 32.0;
    if (f(t) < f(best)) best = t;
  }
  for (int i = 0; i < 4; ++i) {  // polish: Newton on f' where f is convex
    const double curvature = d2f(best);
    if (!(curvature > 0.0)) break;
    const double t = std::clamp(best - df(best) / curvature, 1e-6, 2.0);
    if (f(t) < f(best)) best = t;
  }
  return f(best) < merit ? best : 0.0;
}

ProjectionResult FastProjection::project(Matrix3X& x) {
  ProjectionResult result;
  m_multipliers.setZero(static_cast<Eigen::Index>(m_constraints.size()));
  if (m_constraints.empty()) return result;
  double merit = evaluate(x);
  result.max_strain = max_edge_strain(m_constraints, x, m_inv_mass);
  Matrix3X best = x;
  Eigen::VectorXd best_multipliers = m_multipliers;  // the correction that led to `best`
  double best_strain = result.max_strain;
  Matrix3X step(x.rows(), 3);

  while (result.max_strain > m_settings.tolerance && result.iterations < m_settings.max_iterations) {
    ++result.iterations;
    const base::Stopwatch watch;
    fill_matrix();
    Eigen::VectorXd mu;
    const double forcing = projection_forcing_term(result.max_strain, m_settings.tolerance);
    const bool solved = solve_newton_system(forcing, mu, result);
    result.solve_s += watch.seconds();
    if (!solved) break;

    // δ = −M⁻¹ Jᵀ μ, with ∇_b C = 2 d / l = −∇_a C.
    step.setZero();
    for (std::size_t k = 0; k < m_constraints.size(); ++k) {
      const EdgeConstraint& c = m_constraints[k];
      const auto e = static_cast<Eigen::Index>(k);
      const Eigen::RowVector3d g = (2.0 * mu[e] / c.rest_m) * m_d.row(e);
      step.row(c.b) -= m_inv_mass[c.b] * g;
      step.row(c.a) += m_inv_mass[c.a] * g;
    }
    const double alpha = line_search(step, merit);
    if (alpha == 0.0) break;  // stalled: no step along δ reduces Σ C²
    x += alpha * step;
    m_multipliers += alpha * mu;
    const double merit_before = merit;
    merit = evaluate(x);
    result.max_strain = max_edge_strain(m_constraints, x, m_inv_mass);
    if (result.max_strain < best_strain) {
      best_strain = result.max_strain;
      best = x;
      best_multipliers = m_multipliers;
    }
    if (alpha < 1.0 && m_settings.stall_fraction > 0.0 &&
        merit > m_settings.stall_fraction * merit_before)
      break;  // stalled (ProjectionSettings::stall_fraction)
  }
  result.converged = result.max_strain <= m_settings.tolerance;
  if (!result.converged && best_strain < result.max_strain) {
    x = best;
    m_multipliers = best_multipliers;  // multipliers() must describe the x returned
    result.max_strain = best_strain;
  }
  return result;
}

void FastProjection::save_state(StateWriter& out) const {
  out.section("fast projection");
  const bool reusable = m_reusable && m_settings.reuse_iterations > 0;
  out.pod(reusable);
  out.pods(reusable ? m_factored_values : std::vector<double>{});
}

void FastProjection::restore_state(StateReader& in) {
  in.section("fast projection");
  m_reusable = in.pod<bool>();
  in.pods(m_factored_values);
  if (!m_reusable) return;
  if (m_factored_values.size() != static_cast<std::size_t>(m_matrix.nonZeros()))
    in.fail("a factorization of " + std::to_string(m_factored_values.size()) +
            " values for a matrix of " + std::to_string(m_matrix.nonZeros()));
  std::copy(m_factored_values.begin(), m_factored_values.end(), m_matrix.valuePtr());
  if (!m_solver->factorize(m_matrix)) in.fail("the saved factorization fails");
}

}  // namespace weft::sim
