#include "sim/integrators/implicit_euler.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "base/check.h"
#include "base/timer.h"
#include "sim/linear/block_conjugate_gradient.h"

namespace weft::sim {

// The 3#V×3#V system (degree of freedom 3i + c is coordinate c of vertex i, which is how the
// row-major #V×3 matrices map to vectors)
//   A = M (1 + h α) + h² K,   K = Σ_pairs [H −H; −H H] + Σ_elements K_e,
// kept as its lower triangle (SparseSpdSolver's contract). Its pattern depends only on the
// terms' elements and the pins, so it is built and analysed once; each step writes the values through
// `slots` — one entry of the compressed matrix's valuePtr per contribution, in the fixed order
// of the constructor's loops — so refilling is one linear pass, without triplets or sorting.
// A pinned vertex's rows and columns are the identity with a zero right-hand side (its DOFs are
// eliminated: Δv = 0 there, and nothing couples it to the free vertices).
struct ImplicitEuler::Impl {
  std::vector<char> pinned;  // #V, inv_mass == 0
  // Pair terms first, then the other terms with stiffness: the order of the pattern and fill.
  std::vector<const PairForceTerm*> pair_terms;
  std::vector<const ForceTerm*> element_terms;
  std::vector<std::size_t> element_counts;  // of every term of the system, to check each step
  SparseMatrix A;                           // 3#V×3#V, lower triangle, kg (1 on pinned DOFs)
  std::vector<int> slots;  // valuePtr index of each contribution, in assembly order
  ImplicitSolveSettings solve_settings;
  std::unique_ptr<SparseSpdSolver> solver;  // direct
  std::unique_ptr<BlockConjugateGradient> cg;  // conjugate gradients
  Eigen::VectorXd last_dv;  // conjugate gradients' warm start
  Matrix3X forces;          // #V×3 scratch, N
  Matrix3X velocity_forces; // #V×3 scratch, N
  Matrix3X kv;              // #V×3 scratch, K v_n, N/s

  Impl(const System& system, const ImplicitSolveSettings& solve);
  // The terms of `system` into pair_terms and element_terms, checking their vertices.
  void sort_terms(const System& system);
  // WEFT_CHECKs that `system` has the structure this was built for.
  void check_structure(const System& system, const Matrix3X& x, const Matrix3X& v) const;
  // Δv = A⁻¹ rhs into dv; false when the solve failed.
  bool solve_system(const Eigen::VectorXd& rhs, Eigen::VectorXd& dv, StepReport& result);
  void build_pattern();
  // Writes A's values for step h at positions x, and kv = K v.
  void fill(const System& system, const Matrix3X& x, const Matrix3X& v, double h_s);
  // h (f − h K v + M (g − α v)) on the free DOFs, 0 on the pinned ones, N·s.
  Eigen::VectorXd right_hand_side(const System& system, const Matrix3X& v, double h_s) const;
  // Holds the normal velocity of each resting contact of `system` that free flight would move
  // into its obstacle at zero: A and rhs as in implicit_euler.h. Returns how many it held.
  int hold_contacts(const System& system, const Matrix3X& v, double h_s, Eigen::VectorXd& rhs);
  // The stored (lower-triangle) entry of A at (row, col), row ≥ col, in A's pattern.
  double& lower_entry(int row, int col);
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

ImplicitEuler::Impl::Impl(const System& system, const ImplicitSolveSettings& solve)
    : solve_settings(solve) {
  system.check();
  const Index n = system.vertex_count();
  pinned.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) pinned[static_cast<std::size_t>(i)] = system.inv_mass[i] == 0.0;
  sort_terms(system);
  forces = Matrix3X::Zero(n, 3);
  kv = Matrix3X::Zero(n, 3);
  build_pattern();
  if (solve.method == ImplicitSolve::direct) {
    solver = make_sparse_spd_solver(solve.backend);
    solver->analyze(A);
  } else {
    cg = std::make_unique<BlockConjugateGradient>(solve.threads);
    cg->analyze(A);
    last_dv = Eigen::VectorXd::Zero(3 * n);
  }
}

// Size and index mismatches are bugs in the caller, checked in release builds too.
void ImplicitEuler::Impl::sort_terms(const System& system) {
  const Index n = system.vertex_count();
  Index stencil[kMaxStencil];
  for (const auto& term : system.terms) {
    element_counts.push_back(term->element_count());
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      const int size = term->stencil_size(e);
      for (int k = 0; k < size; ++k)
        WEFT_CHECK(stencil[k] >= 0 && stencil[k] < n,
                   "ImplicitEuler: " + term->describe() + ": element " + std::to_string(e) +
                       " names vertex " + std::to_string(stencil[k]) + " of " + std::to_string(n));
      WEFT_CHECK(!(size == 2 && stencil[0] == stencil[1]),
                 "ImplicitEuler: " + term->describe() + ": element " + std::to_string(e) +
                     " joins vertex " + std::to_string(stencil[0]) + " to itself");
    }
    if (const auto* pairs = dynamic_cast<const PairForceTerm*>(term.get())) {
      pair_terms.push_back(pairs);
    } else if (term->has_stiffness()) {
      element_terms.push_back(term.get());
    }
  }
}

void ImplicitEuler::Impl::check_structure(const System& system, const Matrix3X& x,
                                          const Matrix3X& v) const {
  const Index n = static_cast<Index>(pinned.size());
  WEFT_CHECK(x.rows() == n && v.rows() == n && system.vertex_count() == n,
             "ImplicitEuler::step: positions or velocities have " +
                 std::to_string(std::min(x.rows(), v.rows())) + " rows, expected " +
                 std::to_string(n));
  bool same = system.terms.size() == element_counts.size();
  for (std::size_t t = 0; same && t < element_counts.size(); ++t)
    same = system.terms[t]->element_count() == element_counts[t];
  WEFT_CHECK(same, "ImplicitEuler::step: the system's terms are not those it was made for");
}

bool ImplicitEuler::Impl::solve_system(const Eigen::VectorXd& rhs, Eigen::VectorXd& dv,
                                       StepReport& result) {
  if (solver) {
    if (!solver->factorize(A)) return false;
    dv = solver->solve(rhs);
    return dv.allFinite();  // NaN/inf in, or a factorization that should have failed
  }
  cg->set_matrix(A);
  dv = last_dv;
  const BlockConjugateGradient::Result r =
      cg->solve(rhs, dv, solve_settings.cg_tolerance, solve_settings.cg_max_iterations);
  result.cg_iterations = r.iterations;
  // Not converging within the cap still leaves a usable (smaller-residual) Δv; a breakdown
  // (non-SPD A, non-finite input) does not.
  if (r.breakdown || !dv.allFinite()) return false;
  last_dv = dv;
  return true;
}

void ImplicitEuler::Impl::build_pattern() {
  const Index n = static_cast<Index>(pinned.size());
  std::size_t pairs = 0;
  for (const PairForceTerm* term : pair_terms) pairs += term->element_count();
  std::vector<Entry> entries;  // contributions in fill() order; duplicates allowed
  entries.reserve(3 * static_cast<std::size_t>(n) + 21 * pairs);
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
  for (const PairForceTerm* term : pair_terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      const auto [a, b] = term->pair(e);
      add_pair_blocks(a, b);
    }
  Index stencil[kMaxStencil];
  for (const ForceTerm* term : element_terms) {
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

// A = M (1 + h α) + h² K on the free DOFs, identity on the pinned ones; kv = K v (all pairs,
// so that a moving pin would be seen by its neighbours; pins have v = 0 here).
void ImplicitEuler::Impl::fill(const System& system, const Matrix3X& x, const Matrix3X& v,
                               double h_s) {
  double* values = A.valuePtr();
  std::fill(values, values + A.nonZeros(), 0.0);
  const Index n = static_cast<Index>(pinned.size());
  std::size_t k = 0;
  for (Index i = 0; i < n; ++i) {
    const double diag = pinned[static_cast<std::size_t>(i)]
                            ? 1.0
                            : system.mass_kg[i] * (1.0 + h_s * system.damping_1_s);
    for (int c = 0; c < 3; ++c) values[slots[k++]] += diag;
  }
  kv.setZero();
  const double h2 = h_s * h_s;
  for (const PairForceTerm* term : pair_terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      const auto [a, b] = term->pair(e);
      k = add_pair(a, b, term->pair_stiffness(x, e, /*project_psd=*/true), v, h2, k);
    }
  ElementMatrix K;
  Index stencil[kMaxStencil];
  for (const ForceTerm* term : element_terms) {
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      term->element_stiffness(x, e, K, /*project_psd=*/true);
      k = add_element(stencil, term->stencil_size(e), K, v, h2, k);
    }
  }
}

Eigen::VectorXd ImplicitEuler::Impl::right_hand_side(const System& system, const Matrix3X& v,
                                                     double h_s) const {
  const Index n = static_cast<Index>(pinned.size());
  Eigen::VectorXd rhs(3 * n);  // N·s
  const Eigen::RowVector3d g = system.gravity_m_s2.transpose();
  const double alpha = system.damping_1_s;
  for (Index i = 0; i < n; ++i) {
    Eigen::RowVector3d bi = Eigen::RowVector3d::Zero();
    if (!pinned[static_cast<std::size_t>(i)])
      bi = h_s * (forces.row(i) - h_s * kv.row(i) + system.mass_kg[i] * (g - alpha * v.row(i)));
    rhs.segment<3>(3 * i) = bi.transpose();
  }
  return rhs;
}

double& ImplicitEuler::Impl::lower_entry(int row, int col) {
  const int* inner = A.innerIndexPtr();
  const int* begin = inner + A.outerIndexPtr()[col];
  const int* end = inner + A.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  WEFT_CHECK(it != end && *it == row, "ImplicitEuler: entry (" + std::to_string(row) + ", " +
                                          std::to_string(col) + ") is not in the pattern");
  return A.valuePtr()[it - inner];
}

// Each held contact i with normal n adds κ n nᵀ to A's block (i, i) and κ n (−n·v_i) to rhs_i,
// κ = kContactWeight × the block's mean diagonal: row i then reads
//   n·Δv_i + (A Δv − rhs)_i·n / κ = −n·v_i,
// so n·v_{n+1} = 0 up to about 1/kContactWeight of the solve's own scale, while the tangential
// rows are unchanged (friction stays with the collide phase). A penalty on the diagonal keeps
// A's pattern and its SPD-ness; it is the limit of Baraff & Witkin's filtered constraint.
int ImplicitEuler::Impl::hold_contacts(const System& system, const Matrix3X& v, double h_s,
                                       Eigen::VectorXd& rhs) {
  constexpr double kContactWeight = 1e6;
  int held = 0;
  for (const ObstacleContact& c : system.contacts) {
    const Index i = c.vertex;
    WEFT_CHECK(i >= 0 && i < static_cast<Index>(pinned.size()), "ImplicitEuler: contact vertex " +
                                                                    std::to_string(i) + " of " +
                                                                    std::to_string(pinned.size()));
    if (pinned[static_cast<std::size_t>(i)]) continue;
    const Vec3& n = c.normal;
    // Free flight over the step: v + h (f/m + g − α v), along n.
    const Vec3 vi = v.row(i).transpose();
    const Vec3 accel = forces.row(i).transpose() / system.mass_kg[i] + system.gravity_m_s2 -
                       system.damping_1_s * vi;
    if (n.dot(vi + h_s * accel) >= 0.0) continue;  // leaving or sliding: not pressed in
    const int d = 3 * static_cast<int>(i);
    const double weight =
        kContactWeight *
        (lower_entry(d, d) + lower_entry(d + 1, d + 1) + lower_entry(d + 2, d + 2)) / 3.0;
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col <= r; ++col) lower_entry(d + r, d + col) += weight * n[r] * n[col];
    rhs.segment<3>(d) -= weight * n.dot(vi) * n;
    ++held;
  }
  return held;
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

ImplicitEuler::ImplicitEuler(const System& system, const ImplicitSolveSettings& solve)
    : m_impl(std::make_unique<Impl>(system, solve)) {}

ImplicitEuler::~ImplicitEuler() = default;

// One Newton step of backward Euler (Baraff & Witkin 1998, with ∂f/∂x = −K, ∂f/∂v = −α M):
//   (M (1 + h α) + h² K) Δv = h (f(x_n) − α M v_n − h K v_n + M g),   v_{n+1} = v_n + Δv.
StepReport ImplicitEuler::step(const System& system, State& state, double h_s) {
  const base::Stopwatch watch;
  Impl& im = *m_impl;
  const Matrix3X& x = state.x;
  Matrix3X& v = state.v;
  im.check_structure(system, x, v);
  im.fill(system, x, v, h_s);
  im.forces.setZero();
  system.add_forces(x, im.forces);  // every term, N
  if (system.has_velocity_forces()) {  // explicitly, at (x_n, v_n)
    im.velocity_forces.setZero(x.rows(), 3);
    system.add_velocity_forces(x, v, state.time_s, im.velocity_forces);
    im.forces += im.velocity_forces;
  }
  Eigen::VectorXd rhs = im.right_hand_side(system, v, h_s);

  StepReport result;
  if (!system.contacts.empty()) result.held_contacts = im.hold_contacts(system, v, h_s, rhs);
  Eigen::VectorXd dv;  // m/s
  result.solved = im.solve_system(rhs, dv, result);
  if (result.solved) {
    for (Index i = 0; i < x.rows(); ++i)
      if (!im.pinned[static_cast<std::size_t>(i)]) v.row(i) += dv.segment<3>(3 * i).transpose();
  }
  state.x += h_s * v;
  result.solve_s = watch.seconds();
  return result;
}

// The direct solver refactorizes every step; only conjugate gradients' warm start carries over.
void ImplicitEuler::save_state(StateWriter& out) const {
  out.section("implicit Euler");
  out.matrix(m_impl->last_dv);
}

void ImplicitEuler::restore_state(StateReader& in) {
  in.section("implicit Euler");
  in.matrix(m_impl->last_dv, m_impl->last_dv.size(), 1);
}

}  // namespace weft::sim
