#include "sim/integrators/implicit_euler.h"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/timer.h"
#include "sim/constraints/carried_tension.h"
#include "sim/energies/spring_hessian.h"

namespace weft::sim {

// The 3#V×3#V system (degree of freedom 3i + c is coordinate c of vertex i, which is how the
// row-major #V×3 matrices map to vectors)
//   A = M (1 + h α) + h² K,   K = Σ_springs [H −H; −H H],  H = spring_hessian_b_projected,
// kept as its lower triangle (SparseSpdSolver's contract). Its pattern depends only on the
// springs and the pins, so it is built and analysed once; each step writes the values through
// `slots` — one entry of the compressed matrix's valuePtr per contribution, in the fixed order
// of the constructor's loops — so refilling is one linear pass, without triplets or sorting.
// A pinned vertex's rows and columns are the identity with a zero right-hand side (its DOFs are
// eliminated: Δv = 0 there, and nothing couples it to the free vertices).
struct ImplicitEuler::Impl {
  MassSpringModel model;     // a copy: the integrator does not depend on its owner's address
  Eigen::VectorXd mass_kg;   // #V
  std::vector<char> pinned;  // #V, inv_mass == 0
  std::vector<EdgeConstraint> tension_edges;  // carried constraint forces (see the header)
  ForceTerms terms;                           // continuum elements (shared, immutable)
  SparseMatrix A;                             // 3#V×3#V, lower triangle, kg (1 on pinned DOFs)
  std::vector<int> slots;  // valuePtr index of each contribution, in assembly order
  ImplicitSolveSettings solve_settings;
  std::unique_ptr<SparseSpdSolver> solver;  // direct
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower, Eigen::DiagonalPreconditioner<double>> cg;
  Eigen::VectorXd last_dv;  // conjugate gradients' warm start
  Matrix3X forces;          // #V×3 scratch, N
  Matrix3X kv;              // #V×3 scratch, K v_n, N/s

  Impl(const MassSpringModel& m, Eigen::VectorXd mass, const Eigen::VectorXd& inv_mass,
       const ImplicitSolveSettings& solve, std::vector<EdgeConstraint> tension, ForceTerms t);
  // Δv = A⁻¹ rhs into dv; false when the solve failed.
  bool solve_system(const Eigen::VectorXd& rhs, Eigen::VectorXd& dv, ImplicitStepResult& result);
  void build_pattern();
  // Writes A's values for step h, damping α at positions x, and kv = K v.
  void fill(const Matrix3X& x, const Matrix3X& v, double h_s, double damping_1_s,
            const Eigen::VectorXd& tension_k);
  // Adds the pair (a, b) with stiffness block H: [H −H; −H H] to K v and h² of it to A, at the
  // slots from k on (in build_pattern()'s order); returns the next slot.
  std::size_t add_pair(Index a, Index b, const Mat3& H, const Matrix3X& v, double h2,
                       std::size_t k);
  // The same for an element of a force term with stencil `vertices` and stiffness K.
  std::size_t add_element(const Index* vertices, int size, const ElementMatrix& K,
                          const Matrix3X& v, double h2, std::size_t k);
};

namespace {

struct Entry {
  int row, col;
};

// The lower-triangle entries of the 3×3 block of vertex rows p, columns q (p ≥ q), in the order
// fill() writes them: row-major over the block, skipping the upper part of a diagonal block.
template <class F>
void for_each_lower_entry(Index p, Index q, F&& visit) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (p != q || c <= r) visit(r, c);
}

// The blocks (a, b) of an element's stiffness that land in the lower triangle, in the order
// build_pattern() and fill() both use: stencil positions a, b with vertex[a] ≥ vertex[b],
// both free.
template <class F>
void for_each_element_block(const Index* vertices, int size, const std::vector<char>& pinned,
                            F&& visit) {
  for (int a = 0; a < size; ++a)
    for (int b = 0; b < size; ++b) {
      const Index p = vertices[a], q = vertices[b];
      if ((p > q || a == b) && !pinned[static_cast<std::size_t>(p)] &&
          !pinned[static_cast<std::size_t>(q)])
        visit(a, b, p, q);
    }
}

}  // namespace

ImplicitEuler::Impl::Impl(const MassSpringModel& m, Eigen::VectorXd mass,
                          const Eigen::VectorXd& inv_mass, const ImplicitSolveSettings& solve,
                          std::vector<EdgeConstraint> tension, ForceTerms t)
    : model(m),
      mass_kg(std::move(mass)),
      tension_edges(std::move(tension)),
      terms(std::move(t)),
      solve_settings(solve) {
  const Index n = static_cast<Index>(mass_kg.size());
  // Size and index mismatches are programming bugs (STYLE 8): std::logic_error, in release too.
  if (inv_mass.size() != n)
    throw std::logic_error("ImplicitEuler: " + std::to_string(inv_mass.size()) +
                           " inverse masses for " + std::to_string(n) + " masses");
  pinned.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) pinned[static_cast<std::size_t>(i)] = inv_mass[i] == 0.0;
  const auto check_pair = [n](Index a, Index b) {
    if (a < 0 || b < 0 || a >= n || b >= n || a == b)
      throw std::logic_error("ImplicitEuler: pair (" + std::to_string(a) + ", " +
                             std::to_string(b) + ") does not join two of the " + std::to_string(n) +
                             " vertices");
  };
  for (const Spring& s : model.springs()) check_pair(s.a, s.b);
  for (const EdgeConstraint& e : tension_edges) check_pair(e.a, e.b);
  Index stencil[kMaxStencil];
  for (const auto& term : terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      for (int k = 0; k < term->stencil_size(e); ++k)
        if (stencil[k] < 0 || stencil[k] >= n)
          throw std::logic_error("ImplicitEuler: " + term->describe() + ": element " +
                                 std::to_string(e) + " names vertex " + std::to_string(stencil[k]) +
                                 " of " + std::to_string(n));
    }
  forces = Matrix3X::Zero(n, 3);
  kv = Matrix3X::Zero(n, 3);
  build_pattern();
  if (solve.method == ImplicitSolve::direct) {
    solver = make_sparse_spd_solver(solve.backend);
    solver->analyze(A);
  } else {
    cg.setTolerance(solve.cg_tolerance);
    cg.setMaxIterations(solve.cg_max_iterations);
    last_dv = Eigen::VectorXd::Zero(3 * n);
  }
}

bool ImplicitEuler::Impl::solve_system(const Eigen::VectorXd& rhs, Eigen::VectorXd& dv,
                                       ImplicitStepResult& result) {
  if (solver) {
    if (!solver->factorize(A)) return false;
    dv = solver->solve(rhs);
    return dv.allFinite();  // NaN/inf in, or a factorization that should have failed
  }
  cg.compute(A);
  dv = cg.solveWithGuess(rhs, last_dv);
  result.cg_iterations = static_cast<int>(cg.iterations());
  // Not converging within the cap still leaves a usable (smaller-residual) Δv; a breakdown
  // (non-SPD A, non-finite input) does not.
  if (cg.info() == Eigen::NumericalIssue || !dv.allFinite()) return false;
  last_dv = dv;
  return true;
}

void ImplicitEuler::Impl::build_pattern() {
  const Index n = static_cast<Index>(mass_kg.size());
  std::vector<Entry> entries;  // contributions in fill() order; duplicates allowed
  entries.reserve(3 * static_cast<std::size_t>(n) + 21 * model.springs().size());
  for (int d = 0; d < 3 * n; ++d) entries.push_back({d, d});  // mass (or identity) diagonal
  const auto add_block = [&](Index p, Index q) {              // requires p ≥ q
    for_each_lower_entry(p, q, [&](int r, int c) { entries.push_back({3 * p + r, 3 * q + c}); });
  };
  // A pair with one pinned end still stiffens its free end: its diagonal block enters A, the
  // coupling to the eliminated DOFs does not.
  const auto add_pair_blocks = [&](Index a, Index b) {
    const bool a_free = !pinned[static_cast<std::size_t>(a)];
    const bool b_free = !pinned[static_cast<std::size_t>(b)];
    if (a_free) add_block(a, a);
    if (b_free) add_block(b, b);
    if (a_free && b_free) add_block(std::max(a, b), std::min(a, b));
  };
  for (const Spring& s : model.springs()) add_pair_blocks(s.a, s.b);
  for (const EdgeConstraint& e : tension_edges) add_pair_blocks(e.a, e.b);
  Index stencil[kMaxStencil];
  for (const auto& term : terms) {
    if (!term->has_stiffness()) continue;
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      for_each_element_block(stencil, term->stencil_size(e), pinned,
                             [&](int, int, Index p, Index q) { add_block(p, q); });
    }
  }

  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(entries.size());
  for (const Entry& e : entries) triplets.emplace_back(e.row, e.col, 1.0);
  A.resize(3 * n, 3 * n);
  A.setFromTriplets(triplets.begin(), triplets.end());  // sums duplicates; compressed
  A.makeCompressed();

  // Slot of each contribution: binary search of its row within its column.
  slots.resize(entries.size());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const Entry& e = entries[k];
    const int* begin = inner + outer[e.col];
    const int* end = inner + outer[e.col + 1];
    const int* it = std::lower_bound(begin, end, e.row);
    slots[k] = static_cast<int>(it - inner);
  }
}

// A = M (1 + h α) + h² K on the free DOFs, identity on the pinned ones; kv = K v (all springs,
// so that a moving pin would be seen by its neighbours; pins have v = 0 here).
void ImplicitEuler::Impl::fill(const Matrix3X& x, const Matrix3X& v, double h_s, double damping_1_s,
                               const Eigen::VectorXd& tension_k) {
  double* values = A.valuePtr();
  std::fill(values, values + A.nonZeros(), 0.0);
  const Index n = static_cast<Index>(mass_kg.size());
  std::size_t k = 0;
  for (Index i = 0; i < n; ++i) {
    const double diag =
        pinned[static_cast<std::size_t>(i)] ? 1.0 : mass_kg[i] * (1.0 + h_s * damping_1_s);
    for (int c = 0; c < 3; ++c) values[slots[k++]] += diag;
  }
  kv.setZero();
  const double h2 = h_s * h_s;
  for (const Spring& s : model.springs()) {
    const Vec3 xa = x.row(s.a).transpose(), xb = x.row(s.b).transpose();
    k = add_pair(s.a, s.b, spring_hessian_b_projected(xa, xb, s.rest_m, s.k_N_m), v, h2, k);
  }
  // A carried tension k > 0 is a zero-rest-length spring: stiffness k I (PSD). Compression
  // (k < 0) would make A indefinite: its force is kept, its stiffness dropped.
  for (std::size_t e = 0; e < tension_edges.size(); ++e) {
    const double stiffness =
        tension_k.size() > 0 ? std::max(0.0, tension_k[static_cast<Eigen::Index>(e)]) : 0.0;
    k = add_pair(tension_edges[e].a, tension_edges[e].b, stiffness * Mat3::Identity(), v, h2, k);
  }
  ElementMatrix K;
  Index stencil[kMaxStencil];
  for (const auto& term : terms) {
    if (!term->has_stiffness()) continue;
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      term->element_stiffness(x, e, K, /*project_psd=*/true);
      k = add_element(stencil, term->stencil_size(e), K, v, h2, k);
    }
  }
}

std::size_t ImplicitEuler::Impl::add_element(const Index* vertices, int size,
                                             const ElementMatrix& K, const Matrix3X& v, double h2,
                                             std::size_t k) {
  for (int a = 0; a < size; ++a)  // K v over the stencil
    for (int b = 0; b < size; ++b)
      kv.row(vertices[a]) +=
          (K.block<3, 3>(3 * a, 3 * b) * v.row(vertices[b]).transpose()).transpose();
  double* values = A.valuePtr();
  for_each_element_block(vertices, size, pinned, [&](int a, int b, Index p, Index q) {
    for_each_lower_entry(p, q,
                         [&](int r, int c) { values[slots[k++]] += h2 * K(3 * a + r, 3 * b + c); });
  });
  return k;
}

std::size_t ImplicitEuler::Impl::add_pair(Index a, Index b, const Mat3& H, const Matrix3X& v,
                                          double h2, std::size_t k) {
  // K v: the pair's rows are [H −H; −H H] (v_a; v_b).
  const Vec3 hdv = H * (v.row(b) - v.row(a)).transpose();
  kv.row(a) -= hdv.transpose();
  kv.row(b) += hdv.transpose();

  double* values = A.valuePtr();
  const Mat3 hH = h2 * H;
  const bool a_free = !pinned[static_cast<std::size_t>(a)];
  const bool b_free = !pinned[static_cast<std::size_t>(b)];
  if (a_free) for_each_lower_entry(a, a, [&](int r, int c) { values[slots[k++]] += hH(r, c); });
  if (b_free) for_each_lower_entry(b, b, [&](int r, int c) { values[slots[k++]] += hH(r, c); });
  if (a_free && b_free) {
    // Block (max, min) of −H; H is symmetric, so the transpose needs no care.
    for_each_lower_entry(std::max(a, b), std::min(a, b),
                         [&](int r, int c) { values[slots[k++]] -= hH(r, c); });
  }
  return k;
}

ImplicitEuler::ImplicitEuler(const MassSpringModel& model, Eigen::VectorXd mass_kg,
                             Eigen::VectorXd inv_mass, const ImplicitSolveSettings& solve,
                             std::vector<EdgeConstraint> tension_edges, ForceTerms terms)
    : m_impl(std::make_unique<Impl>(model, std::move(mass_kg), inv_mass, solve,
                                    std::move(tension_edges), std::move(terms))) {}

ImplicitEuler::~ImplicitEuler() = default;

// One Newton step of backward Euler (Baraff & Witkin 1998, with ∂f/∂x = −K, ∂f/∂v = −α M):
//   (M (1 + h α) + h² K) Δv = h (f(x_n) − α M v_n − h K v_n + M g),   v_{n+1} = v_n + Δv.
ImplicitStepResult ImplicitEuler::step(const Matrix3X& x, Matrix3X& v, double h_s,
                                       const Vec3& gravity_m_s2, double damping_1_s,
                                       const Eigen::VectorXd& tension_k,
                                       const Matrix3X& external_forces) {
  const base::Stopwatch watch;
  Impl& im = *m_impl;
  const Index n = static_cast<Index>(im.mass_kg.size());
  if (x.rows() != n || v.rows() != n)
    throw std::logic_error("ImplicitEuler::step: positions or velocities have " +
                           std::to_string(std::min(x.rows(), v.rows())) + " rows, expected " +
                           std::to_string(n));

  if (tension_k.size() != 0 &&
      tension_k.size() != static_cast<Eigen::Index>(im.tension_edges.size()))
    throw std::logic_error("ImplicitEuler::step: " + std::to_string(tension_k.size()) +
                           " tensions for " + std::to_string(im.tension_edges.size()) + " edges");
  im.fill(x, v, h_s, damping_1_s, tension_k);
  im.forces.setZero();
  im.model.add_forces(x, im.forces);  // springs and bending, N
  for (const auto& term : im.terms) term->add_forces(x, im.forces);
  add_tension_forces(im.tension_edges, tension_k, x, im.forces);
  if (external_forces.rows() != 0 && external_forces.rows() != n)
    throw std::logic_error("ImplicitEuler::step: " + std::to_string(external_forces.rows()) +
                           " external forces for " + std::to_string(n) + " vertices");
  if (external_forces.rows() == n) im.forces += external_forces;

  Eigen::VectorXd rhs(3 * n);  // N·s
  const Eigen::RowVector3d g = gravity_m_s2.transpose();
  for (Index i = 0; i < n; ++i) {
    Eigen::RowVector3d bi = Eigen::RowVector3d::Zero();
    if (!im.pinned[static_cast<std::size_t>(i)])
      bi = h_s *
           (im.forces.row(i) - h_s * im.kv.row(i) + im.mass_kg[i] * (g - damping_1_s * v.row(i)));
    rhs.segment<3>(3 * i) = bi.transpose();
  }

  ImplicitStepResult result;
  Eigen::VectorXd dv;  // m/s
  result.solved = im.solve_system(rhs, dv, result);
  if (result.solved) {
    for (Index i = 0; i < n; ++i)
      if (!im.pinned[static_cast<std::size_t>(i)]) v.row(i) += dv.segment<3>(3 * i).transpose();
  }
  result.solve_s = watch.seconds();
  return result;
}

}  // namespace weft::sim
