#pragma once
// Internal to sim/linear: the bookkeeping every SparseSpdSolver back-end shares — the analysed
// sparsity pattern (so that factorizing a different pattern is caught as the programming bug it
// is, instead of reading past the symbolic factor) and the input checks (WEFT_CHECK: misuse is a
// bug, base::InternalError, checked in release builds too).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "base/check.h"
#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim::linear_detail {

// "SparseSpdSolver (cholmod): what": the message of a failed check.
inline std::string misuse_message(const char* backend, const std::string& what) {
  return std::string("SparseSpdSolver (") + backend + "): " + what;
}

// A copy of a compressed matrix's structure: n, column starts and row indices.
class SparsityPattern {
 public:
  SparsityPattern() = default;
  explicit SparsityPattern(const SparseMatrix& A)
      : m_size(A.rows()),
        m_outer(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1),
        m_inner(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros()) {}

  bool empty() const { return m_outer.empty(); }
  Eigen::Index size() const { return m_size; }

  // O(nnz): negligible beside a numeric factorization.
  bool matches(const SparseMatrix& A) const {
    return A.rows() == m_size && A.cols() == m_size && A.isCompressed() &&
           std::equal(m_outer.begin(), m_outer.end(), A.outerIndexPtr()) &&
           A.nonZeros() == static_cast<Eigen::Index>(m_inner.size()) &&
           std::equal(m_inner.begin(), m_inner.end(), A.innerIndexPtr());
  }

 private:
  Eigen::Index m_size = 0;
  std::vector<int> m_outer, m_inner;
};

// The checks analyze() makes: square and compressed.
inline void require_analyzable(const SparseMatrix& A, const char* backend) {
  WEFT_CHECK(
      A.rows() == A.cols(),
      misuse_message(backend, "analyze: the matrix must be square, got " +
                                  std::to_string(A.rows()) + "x" + std::to_string(A.cols())));
  WEFT_CHECK(A.isCompressed(),
             misuse_message(backend, "analyze: the matrix must be compressed (makeCompressed())"));
}

// The checks factorize() makes: analysed, and the same pattern.
inline void require_analysed_pattern(const SparsityPattern& pattern, const SparseMatrix& A,
                                     const char* backend) {
  WEFT_CHECK(!pattern.empty(), misuse_message(backend, "factorize called before analyze"));
  WEFT_CHECK(
      pattern.matches(A),
      misuse_message(backend,
                     "factorize: the matrix's sparsity pattern differs from the analysed one "
                     "(call analyze again when the pattern changes)"));
}

// Index of the first stored entry that is NaN or ±inf, or −1.
inline Eigen::Index first_non_finite_entry(const SparseMatrix& A) {
  const double* values = A.valuePtr();
  const double* end = values + A.nonZeros();
  const double* bad = std::find_if(values, end, [](double v) { return !std::isfinite(v); });
  return bad == end ? -1 : static_cast<Eigen::Index>(bad - values);
}

inline std::string non_finite_entry_message(const SparseMatrix& A, Eigen::Index entry) {
  // Column of stored entry `entry`: the last column start not after it.
  const int* outer = A.outerIndexPtr();
  const auto column =
      std::upper_bound(outer, outer + A.outerSize() + 1, static_cast<int>(entry)) - outer - 1;
  return "entry (" + std::to_string(A.innerIndexPtr()[entry]) + ", " + std::to_string(column) +
         ") is " + std::to_string(A.valuePtr()[entry]);
}

// "pivot 17 of 480 is -3.2e-04" (pivots counted from 0 in the permuted order).
inline std::string pivot_message(Eigen::Index pivot, Eigen::Index n, double value) {
  char text[96];
  std::snprintf(text, sizeof(text), "pivot %ld of %ld is %.3e", static_cast<long>(pivot),
                static_cast<long>(n), value);
  return text;
}

// The preconditions of solve(): a successful factorization, and a right-hand side of the
// analysed size. Otherwise a bug (base::InternalError).
inline void require_solvable(bool factorized, const SparsityPattern& pattern,
                             const Eigen::VectorXd& b, const char* backend) {
  WEFT_CHECK(factorized, misuse_message(backend, "solve called without a successful factorize"));
  WEFT_CHECK(b.size() == pattern.size(),
             misuse_message(backend, "solve: the right-hand side has " + std::to_string(b.size()) +
                                         " rows, the matrix " + std::to_string(pattern.size())));
}

}  // namespace weft::sim::linear_detail
