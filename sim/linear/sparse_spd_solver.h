#pragma once
// Sparse symmetric positive (semi-)definite solves with the sparsity pattern analysed once and
// only the numeric factorization repeated. Back-ends chosen by name.

#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "base/enum_names.h"

namespace weft::sim {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

enum class SparseBackend { eigen_ldlt, cholmod };

// The back-ends' names (simulation.linear_solver), in the order an error lists them.
inline constexpr base::EnumNames<SparseBackend, 2> sparse_backend_names{
    {{SparseBackend::cholmod, "cholmod"}, {SparseBackend::eigen_ldlt, "eigen_ldlt"}}};

// "eigen_ldlt", "cholmod"; throws std::invalid_argument listing the known names.
SparseBackend sparse_backend_from_name(const std::string& name);
inline const char* sparse_backend_name(SparseBackend backend) {
  return base::enum_name(sparse_backend_names, backend);
}
// The back-ends this build has (cholmod only when built with CHOLMOD).
std::vector<SparseBackend> available_sparse_backends();
// The default: the faster of the available back-ends as measured by bench/sparse_solver_bench.
SparseBackend default_sparse_backend();

// Misuse — factorize() before analyze(), a pattern other than the analysed one, solve() without
// a successful factorize(), a right-hand side of the wrong size — is a bug (base::InternalError).
// One object must not be used from two threads at once (solve() reuses workspace).
class SparseSpdSolver {
 public:
  virtual ~SparseSpdSolver() = default;
  // Symbolic analysis (fill-reducing ordering, elimination tree) of A's pattern; call once per
  // pattern. A is symmetric; only its lower triangle need be filled.
  virtual void analyze(const SparseMatrix& A) = 0;
  // Numeric factorization of A with the analysed pattern. Returns false when A is not
  // numerically positive definite (a zero, negative or non-finite pivot, or a non-finite entry).
  [[nodiscard]] virtual bool factorize(const SparseMatrix& A) = 0;
  // x = A⁻¹ b with the last factorization.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) const = 0;
  virtual SparseBackend backend() const = 0;
  // Why the last factorize() returned false (e.g. "pivot 17 of 480 is -3.2e-04"), for
  // diagnostics; empty after a successful one.
  virtual std::string last_failure() const = 0;
};

// Throws std::invalid_argument when the back-end is not in this build.
std::unique_ptr<SparseSpdSolver> make_sparse_spd_solver(SparseBackend backend);

}  // namespace weft::sim
