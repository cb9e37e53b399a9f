#include "sim/statics/static_equilibrium.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <memory>
#include <random>

#include "base/check.h"
#include "base/format.h"
#include "sim/linear/cholmod_solver.h"
#include "sim/linear/stiffness_assembly.h"

namespace weft::sim {
namespace {

constexpr double kArmijo = 1e-4;
constexpr double kSmallestStep = 1e-10;  // line-search α below which the shift μ is raised
constexpr int kMaxShiftRaises = 40;
constexpr double kExactBelow = 1.0;  // residual below which the exact Hessian is tried
constexpr int kExactPause = 10;       // iterations without it after it failed

// The Levenberg–Marquardt shift μ, 1/s² (μ M is N/m): never below `floor` (which keeps the
// rigid motions a pinless or frictionless cloth has from making K singular), raised ×10 when a
// step fails, lowered ÷3 after a step whose first trial was accepted.
struct Shift {
  double value = 0.0;
  double floor = 0.0;
  void raise() { value = std::max(10.0 * value, floor); }
  void relax() { value = std::max(value / 3.0, floor); }
};

double squared_free_norm(const Matrix3X& g, const Eigen::VectorXd& inv_mass) {
  double sum = 0.0;
  for (Index i = 0; i < g.rows(); ++i)
    if (inv_mass[i] > 0.0) sum += g.row(i).squaredNorm();
  return sum;
}

// A static solve factorizes one matrix per Newton iteration, hundreds of times: CHOLMOD's
// supernodal factorization (dense blocks through BLAS) when weft has CHOLMOD, Eigen's LDLᵀ
// otherwise.
std::unique_ptr<SparseSpdSolver> make_static_solver() {
  if (default_sparse_backend() != SparseBackend::cholmod)
    return make_sparse_spd_solver(default_sparse_backend());
  CholmodSettings settings;
  settings.factorization = CholmodFactorization::supernodal;
  return make_cholmod_solver(settings);
}

}  // namespace

StaticEquilibrium::StaticEquilibrium(const System& system, std::vector<Obstacle> obstacles,
                                     double thickness_m, double mean_edge_m,
                                     double shortest_edge_m, const StaticSettings& settings)
    : m_system(system),
      m_obstacles(std::move(obstacles)),
      m_thickness_m(thickness_m),
      m_mean_edge_m(mean_edge_m),
      m_shortest_edge_m(shortest_edge_m),
      m_settings(settings) {
  system.check();
  WEFT_CHECK(thickness_m > 0.0 || m_obstacles.empty(),
             "StaticEquilibrium: obstacles need a collision thickness > 0");
  WEFT_CHECK(mean_edge_m > 0.0 && shortest_edge_m > 0.0,
             "StaticEquilibrium: rest edge lengths must be > 0");
  WEFT_CHECK(settings.tolerance > 0.0 && settings.max_iterations > 0 &&
                 settings.contact_stiffness > 0.0 && settings.imperfection >= 0.0 &&
                 settings.max_move > 0.0,
             "StaticEquilibrium: bad settings");
  const double g = system.gravity_m_s2.norm();
  m_contact_k = Eigen::VectorXd::Zero(system.vertex_count());
  if (!m_obstacles.empty()) {
    // Without gravity the weight scale is the mean vertex's under 1 g.
    const double load = g > 0.0 ? g : 9.80665;
    m_contact_k = settings.contact_stiffness * load / thickness_m * system.mass_kg;
  }
}

StaticEquilibrium::~StaticEquilibrium() = default;

double StaticEquilibrium::energy(const Matrix3X& x) const {
  double e = m_system.energy(x);
  for (Index i = 0; i < x.rows(); ++i) {
    if (m_system.inv_mass[i] == 0.0) continue;
    const Vec3 p = x.row(i).transpose();
    e -= m_system.mass_kg[i] * m_system.gravity_m_s2.dot(p);
    for (const Obstacle& o : m_obstacles) {
      const double depth = m_thickness_m - signed_distance(o, p);
      if (depth > 0.0) e += 0.5 * m_contact_k[i] * depth * depth;
    }
  }
  return e;
}

Matrix3X StaticEquilibrium::gradient(const Matrix3X& x) const {
  Matrix3X f = Matrix3X::Zero(x.rows(), 3);
  m_system.add_forces(x, f);
  Matrix3X g(x.rows(), 3);
  for (Index i = 0; i < x.rows(); ++i) {
    if (m_system.inv_mass[i] == 0.0) {
      g.row(i).setZero();
      continue;
    }
    const Vec3 p = x.row(i).transpose();
    Vec3 gi = -f.row(i).transpose() - m_system.mass_kg[i] * m_system.gravity_m_s2;
    for (const Obstacle& o : m_obstacles) {
      const double depth = m_thickness_m - signed_distance(o, p);
      if (depth > 0.0) gi -= m_contact_k[i] * depth * outward_normal(o, p);
    }
    g.row(i) = gi.transpose();
  }
  return g;
}

int StaticEquilibrium::add_contact_blocks(const Matrix3X& x, StiffnessAssembly& assembly) const {
  int contacts = 0;
  for (Index i = 0; i < x.rows(); ++i) {
    if (m_system.inv_mass[i] == 0.0) continue;
    const Vec3 p = x.row(i).transpose();
    bool touching = false;
    for (const Obstacle& o : m_obstacles) {
      if (signed_distance(o, p) >= m_thickness_m) continue;
      const Vec3 n = outward_normal(o, p);
      assembly.add_diagonal_block(i, m_contact_k[i] * n * n.transpose());
      touching = true;
    }
    contacts += touching ? 1 : 0;
  }
  return contacts;
}

void StaticEquilibrium::perturb(Matrix3X& x) const {
  const double amplitude = m_settings.imperfection * m_mean_edge_m;
  if (amplitude == 0.0) return;
  std::mt19937_64 rng(m_settings.seed);
  // Uniform in [−1, 1) from the raw bits: the same numbers on every standard library.
  const auto unit = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-52 - 1.0; };
  for (Index i = 0; i < x.rows(); ++i) {
    const Vec3 d(unit(), unit(), unit());
    if (m_system.inv_mass[i] > 0.0) x.row(i) += amplitude * d.transpose();
  }
}

// One solve's working state: the assembled matrix and its factorization, the shift, the trust
// radius and the current point's energy and gradient.
struct StaticEquilibrium::Newton {
  const StaticEquilibrium& statics;
  StiffnessAssembly assembly;
  std::unique_ptr<SparseSpdSolver> solver;
  Shift shift;
  double radius_m;  // the most a vertex moves in one step
  double energy_J = 0.0;
  Matrix3X g;
  int exact_blocked = 0;  // iterations left before the exact Hessian is tried again

  Newton(const StaticEquilibrium& s, const Matrix3X& x)
      : statics(s),
        assembly(s.m_system, StiffnessAssembly::Terms::all, "StaticEquilibrium"),
        solver(make_static_solver()),
        radius_m(s.m_settings.max_move * s.m_shortest_edge_m),
        energy_J(s.energy(x)),
        g(s.gradient(x)) {
    solver->analyze(assembly.matrix());
    shift.floor = shift_floor(x);
    shift.value = shift.floor;
  }

  // 1e-8 of the mean of diag(K)/m over the free DOFs at x, 1/s².
  double shift_floor(const Matrix3X& x) {
    const Eigen::VectorXd& inv_mass = statics.m_system.inv_mass;
    assembly.fill(x, Eigen::VectorXd::Zero(x.rows()), 1.0);
    double sum = 0.0;
    long count = 0;
    for (Index i = 0; i < x.rows(); ++i)
      if (inv_mass[i] > 0.0)
        for (int c = 0; c < 3; ++c, ++count)
          sum += assembly.lower_entry(3 * i + c, 3 * i + c) * inv_mass[i];
    return count > 0 ? 1e-8 * std::max(sum / static_cast<double>(count), 1e-12) : 1e-8;
  }

  // The Newton direction p = −(K + μ M)⁻¹ ∇Π, exact Hessian or PSD-projected; false when the
  // factorization fails or p does not descend.
  bool direction(const Matrix3X& x, bool exact, Eigen::VectorXd& p, StaticResult& result) {
    assembly.fill(x, shift.value * statics.m_system.mass_kg, 1.0, nullptr, nullptr, !exact);
    statics.add_contact_blocks(x, assembly);
    ++result.factorizations;
    if (!solver->factorize(assembly.matrix())) return false;
    // Matrix3X is row-major #V×3: its storage is the DOF order 3i + c.
    const Eigen::Map<const Eigen::VectorXd> gv(g.data(), g.size());
    p = -solver->solve(gv);
    return p.allFinite() && p.dot(gv) < 0.0;
  }

  // The largest α ≤ 1 at which no vertex moves more than the trust radius, nor, near an
  // obstacle, more than max(δ, its distance to the nearest surface): it can reach the surface
  // but never jump through the obstacle, whose penalty then stops it.
  double longest_step(const Matrix3X& x, const Eigen::Map<const Matrix3X>& step) const {
    double alpha = 1.0;
    for (Index i = 0; i < x.rows(); ++i) {
      const double move = step.row(i).norm();
      if (move == 0.0) continue;
      double cap = radius_m;
      if (!statics.m_obstacles.empty()) {
        double d = std::numeric_limits<double>::infinity();
        for (const Obstacle& o : statics.m_obstacles)
          d = std::min(d, signed_distance(o, x.row(i).transpose()));
        cap = std::min(cap, std::max(statics.m_thickness_m, d));
      }
      alpha = std::min(alpha, cap / move);
    }
    return alpha;
  }

  // What a line search took: whether at its first (capped) length, whether the cap shortened
  // the Newton step, and the most a vertex moved, m.
  struct StepTaken {
    bool whole = false, capped = false;
    double moved_m = 0.0;
  };

  // Backtracking from the step capped to the trust radius; moves x and returns true when a step
  // was taken.
  bool line_search(Matrix3X& x, const Eigen::VectorXd& p, StepTaken& taken) {
    const Eigen::VectorXd& inv_mass = statics.m_system.inv_mass;
    const Eigen::Map<const Matrix3X> step(p.data(), x.rows(), 3);
    const double first_alpha = longest_step(x, step);
    const double slope = p.dot(Eigen::Map<const Eigen::VectorXd>(g.data(), g.size()));
    for (double alpha = first_alpha; alpha >= kSmallestStep; alpha *= 0.5) {
      Matrix3X trial = x + alpha * step;
      const double e = statics.energy(trial);
      bool accept = std::isfinite(e) && e <= energy_J + kArmijo * alpha * slope;
      Matrix3X g_trial;
      // Near the minimum Π's decrease is below its rounding (|Π| ε): a first step that lowers
      // the residual is then taken on the residual's word.
      if (!accept && alpha == first_alpha &&
          std::abs(kArmijo * alpha * slope) < 1e-12 * std::abs(energy_J)) {
        g_trial = statics.gradient(trial);
        accept = squared_free_norm(g_trial, inv_mass) < squared_free_norm(g, inv_mass);
      }
      if (!accept) continue;
      x = std::move(trial);
      energy_J = e;
      g = g_trial.size() ? std::move(g_trial) : statics.gradient(x);
      taken = {alpha == first_alpha, first_alpha < 1.0, alpha * step.rowwise().norm().maxCoeff()};
      return true;
    }
    return false;
  }

  // One iteration: false when no descent step was found even with the shift raised.
  bool iterate(Matrix3X& x, StaticResult& result) {
    for (int raises = 0; raises <= kMaxShiftRaises; ++raises) {
      // Near a stable equilibrium the exact Hessian is positive definite and converges
      // quadratically; the projected one, exact only where nothing is compressed or bent
      // beyond its rest, converges linearly.
      const bool exact = exact_blocked == 0 && result.residual < kExactBelow;
      Eigen::VectorXd p;
      StepTaken taken;
      if (direction(x, exact, p, result) && line_search(x, p, taken)) {
        // The radius grows only while it binds, and shrinks to what a backtracked step moved:
        // it stays within twice the longest step taken.
        if (taken.whole) {
          shift.relax();
          if (taken.capped) radius_m *= 2.0;
        } else {
          radius_m = taken.moved_m;
        }
        exact_blocked = std::max(0, exact_blocked - 1);
        return true;
      }
      if (exact) {
        exact_blocked = kExactPause;
        continue;
      }
      shift.raise();
    }
    return false;
  }
};

StaticResult StaticEquilibrium::solve(Matrix3X& x) const {
  WEFT_CHECK(x.rows() == m_system.vertex_count(), "StaticEquilibrium::solve: wrong size");
  perturb(x);
  double load2 = 0.0;  // ‖M g‖² over the free vertices
  for (Index i = 0; i < x.rows(); ++i)
    if (m_system.inv_mass[i] > 0.0)
      load2 += std::pow(m_system.mass_kg[i], 2) * m_system.gravity_m_s2.squaredNorm();
  const double load = load2 > 0.0 ? std::sqrt(load2) : 1.0;

  Newton newton(*this, x);
  StaticResult result;
  for (;; ++result.iterations) {
    result.residual = std::sqrt(squared_free_norm(newton.g, m_system.inv_mass)) / load;
    if (!std::isfinite(result.residual)) {
      result.stopped = "the residual is not finite";
      break;
    }
    if (result.residual <= m_settings.tolerance) {
      result.converged = true;
      break;
    }
    if (result.iterations == m_settings.max_iterations) {
      result.stopped = "not converged in " + std::to_string(m_settings.max_iterations) +
                       " iterations (residual " + base::format("%.3g", result.residual) + ")";
      break;
    }
    if (!newton.iterate(x, result)) {
      result.stopped = "no descent step found (residual " + base::format("%.3g", result.residual) + ")";
      break;
    }
  }
  result.energy_J = newton.energy_J;
  newton.assembly.fill(x, Eigen::VectorXd::Zero(x.rows()), 1.0);
  result.contacts = add_contact_blocks(x, newton.assembly);
  return result;
}

}  // namespace weft::sim
