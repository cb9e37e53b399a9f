#include "sim/linear/stiffness_assembly.h"

#include <algorithm>
#include <string>

#include "base/check.h"

namespace weft::sim {
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

StiffnessAssembly::StiffnessAssembly(const System& system, Terms terms, const char* who)
    : m_time_step(terms == Terms::time_step) {
  system.check();
  const Index n = system.vertex_count();
  m_pinned.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) m_pinned[static_cast<std::size_t>(i)] = system.inv_mass[i] == 0.0;
  sort_terms(system, terms, who);
  build_pattern();
}

// Size and index mismatches are bugs in the caller, checked in release builds too.
void StiffnessAssembly::sort_terms(const System& system, Terms terms, const char* who) {
  const Index n = system.vertex_count();
  const std::string prefix = std::string(who) + ": ";
  Index stencil[kMaxStencil];
  for (const auto& term : system.terms) {
    m_element_counts.push_back(term->element_count());
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      const int size = term->stencil_size(e);
      for (int k = 0; k < size; ++k)
        WEFT_CHECK(stencil[k] >= 0 && stencil[k] < n,
                   prefix + term->describe() + ": element " + std::to_string(e) +
                       " names vertex " + std::to_string(stencil[k]) + " of " + std::to_string(n));
      WEFT_CHECK(!(size == 2 && stencil[0] == stencil[1]),
                 prefix + term->describe() + ": element " + std::to_string(e) +
                     " joins vertex " + std::to_string(stencil[0]) + " to itself");
    }
    if (const auto* pairs = dynamic_cast<const PairForceTerm*>(term.get())) {
      m_pair_terms.push_back(pairs);
    } else if (term->has_stiffness() &&
               (terms == Terms::all || term->stiffness_in_time_step())) {
      m_element_terms.push_back(term.get());
    }
  }
}

void StiffnessAssembly::check_structure(const System& system, const char* who) const {
  bool same = system.vertex_count() == static_cast<Index>(m_pinned.size()) &&
              system.terms.size() == m_element_counts.size();
  for (std::size_t t = 0; same && t < m_element_counts.size(); ++t)
    same = system.terms[t]->element_count() == m_element_counts[t];
  WEFT_CHECK(same, std::string(who) + ": the system's terms are not those it was made for");
}

void StiffnessAssembly::build_pattern() {
  const Index n = static_cast<Index>(m_pinned.size());
  std::size_t pairs = 0;
  for (const PairForceTerm* term : m_pair_terms) pairs += term->element_count();
  std::vector<Entry> entries;  // contributions in fill() order; duplicates allowed
  entries.reserve(3 * static_cast<std::size_t>(n) + 21 * pairs);
  for (int d = 0; d < 3 * n; ++d) entries.push_back({d, d});  // the diagonal d (or identity)
  const auto add_block = [&](Index p, Index q) {             // requires p ≥ q
    for_each_lower_entry(p, q, [&](int r, int c) { entries.push_back({3 * p + r, 3 * q + c}); });
  };
  // A pair with one pinned end still stiffens its free end: its diagonal block enters A, the
  // coupling to the eliminated DOFs does not.
  for (const PairForceTerm* term : m_pair_terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      const auto [a, b] = term->pair(e);
      const bool a_free = !pinned(a), b_free = !pinned(b);
      if (a_free) add_block(a, a);
      if (b_free) add_block(b, b);
      if (a_free && b_free) add_block(std::max(a, b), std::min(a, b));
    }
  Index stencil[kMaxStencil];
  for (const ForceTerm* term : m_element_terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      for_each_element_block(stencil, term->stencil_size(e), m_pinned,
                             [&](int, int, Index p, Index q) { add_block(p, q); });
    }

  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(entries.size() + 3 * static_cast<std::size_t>(n));
  for (const Entry& e : entries) triplets.emplace_back(e.row, e.col, 1.0);
  // Structural entries only (no contribution of their own): every free diagonal block.
  for (Index i = 0; i < n; ++i)
    if (!pinned(i))
      for_each_lower_entry(i, i, [&](int r, int c) { triplets.emplace_back(3 * i + r, 3 * i + c, 1.0); });
  m_A.resize(3 * n, 3 * n);
  m_A.setFromTriplets(triplets.begin(), triplets.end());  // sums duplicates; compressed
  m_A.makeCompressed();

  // Slot of each contribution: binary search of its row within its column.
  m_slots.resize(entries.size());
  const int* outer = m_A.outerIndexPtr();
  const int* inner = m_A.innerIndexPtr();
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const Entry& e = entries[k];
    const int* begin = inner + outer[e.col];
    const int* end = inner + outer[e.col + 1];
    m_slots[k] = static_cast<int>(std::lower_bound(begin, end, e.row) - inner);
  }
}

void StiffnessAssembly::fill(const Matrix3X& x, const Eigen::VectorXd& d, double s,
                             const Matrix3X* v, Matrix3X* kv, bool project_psd) {
  double* values = m_A.valuePtr();
  std::fill(values, values + m_A.nonZeros(), 0.0);
  const Index n = static_cast<Index>(m_pinned.size());
  std::size_t k = 0;
  for (Index i = 0; i < n; ++i) {
    const double diag = pinned(i) ? 1.0 : d[i];
    for (int c = 0; c < 3; ++c) values[m_slots[k++]] += diag;
  }
  if (kv) kv->setZero();
  for (const PairForceTerm* term : m_pair_terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      const auto [a, b] = term->pair(e);
      k = add_pair(a, b, term->pair_stiffness(x, e, project_psd), s, v, kv, k);
    }
  ElementMatrix K;
  Index stencil[kMaxStencil];
  for (const ForceTerm* term : m_element_terms)
    for (std::size_t e = 0; e < term->element_count(); ++e) {
      term->stencil(e, stencil);
      if (m_time_step && project_psd)
        term->time_step_stiffness(x, e, K);
      else
        term->element_stiffness(x, e, K, project_psd);
      k = add_element(stencil, term->stencil_size(e), K, s, v, kv, k);
    }
}

double& StiffnessAssembly::lower_entry(int row, int col) {
  const int* inner = m_A.innerIndexPtr();
  const int* begin = inner + m_A.outerIndexPtr()[col];
  const int* end = inner + m_A.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  WEFT_CHECK(it != end && *it == row, "StiffnessAssembly: entry (" + std::to_string(row) + ", " +
                                          std::to_string(col) + ") is not in the pattern");
  return m_A.valuePtr()[it - inner];
}

void StiffnessAssembly::add_diagonal_block(Index i, const Mat3& B) {
  WEFT_CHECK(i >= 0 && i < static_cast<Index>(m_pinned.size()) && !pinned(i),
             "StiffnessAssembly: diagonal block of vertex " + std::to_string(i) +
                 ", which is pinned or out of range");
  const int d = 3 * static_cast<int>(i);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c <= r; ++c) lower_entry(d + r, d + c) += B(r, c);
}

std::size_t StiffnessAssembly::add_element(const Index* vertices, int size, const ElementMatrix& K,
                                           double s, const Matrix3X* v, Matrix3X* kv,
                                           std::size_t k) {
  if (kv)  // K v over the stencil
    for (int a = 0; a < size; ++a)
      for (int b = 0; b < size; ++b)
        kv->row(vertices[a]) +=
            (K.block<3, 3>(3 * a, 3 * b) * v->row(vertices[b]).transpose()).transpose();
  double* values = m_A.valuePtr();
  for_each_element_block(vertices, size, m_pinned, [&](int a, int b, Index p, Index q) {
    for_each_lower_entry(p, q,
                         [&](int r, int c) { values[m_slots[k++]] += s * K(3 * a + r, 3 * b + c); });
  });
  return k;
}

std::size_t StiffnessAssembly::add_pair(Index a, Index b, const Mat3& H, double s,
                                        const Matrix3X* v, Matrix3X* kv, std::size_t k) {
  if (kv) {  // K v: the pair's rows are [H −H; −H H] (v_a; v_b)
    const Vec3 hdv = H * (v->row(b) - v->row(a)).transpose();
    kv->row(a) -= hdv.transpose();
    kv->row(b) += hdv.transpose();
  }
  double* values = m_A.valuePtr();
  const Mat3 sH = s * H;
  const bool a_free = !pinned(a), b_free = !pinned(b);
  if (a_free) for_each_lower_entry(a, a, [&](int r, int c) { values[m_slots[k++]] += sH(r, c); });
  if (b_free) for_each_lower_entry(b, b, [&](int r, int c) { values[m_slots[k++]] += sH(r, c); });
  if (a_free && b_free) {
    // Block (max, min) of −H; H is symmetric, so the transpose needs no care.
    for_each_lower_entry(std::max(a, b), std::min(a, b),
                         [&](int r, int c) { values[m_slots[k++]] -= sH(r, c); });
  }
  return k;
}

}  // namespace weft::sim
