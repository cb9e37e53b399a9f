#pragma once
// Conjugate gradients for implicit Euler's 3#V system (sim/integrators/implicit_euler.h), with
// a 3×3 block-Jacobi preconditioner (the inverse of each vertex's diagonal block) and the
// matrix–vector product shared among threads.
//
// The system arrives as SparseSpdSolver takes it: the lower triangle, column-major. analyze()
// builds a full (both triangles) row-major copy of its pattern once; set_matrix() scatters the
// values into it. Each thread multiplies a contiguous range of rows, and every row is one
// sequential dot product, so the product — and with the sequential vector updates and dot
// products, every iterate — is the same bits for any number of threads (DESIGN.md,
// Determinism).
//
// Stops at ‖b − A x‖ ≤ tolerance ‖b‖ (the convention of Eigen::ConjugateGradient, which this
// replaces) or after max_iterations; either way x is the last iterate.

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "base/thread_pool.h"
#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim {

class BlockConjugateGradient {
 public:
  struct Result {
    int iterations = 0;
    double relative_residual = 0.0;  // ‖b − A x‖ / ‖b‖ at the end
    bool breakdown = false;  // a non-positive curvature pᵀAp or preconditioner rᵀz: A or its
                             // diagonal blocks are not positive definite, or not finite
  };

  // threads: as base::thread_count (0 = all hardware threads).
  explicit BlockConjugateGradient(int threads);
  ~BlockConjugateGradient();

  // The pattern of `lower` (square, 3k rows, lower triangle, compressed). Once per pattern.
  void analyze(const SparseMatrix& lower);
  // The values of `lower` (the analysed pattern) and the inverses of its 3×3 diagonal blocks.
  void set_matrix(const SparseMatrix& lower);
  // From the initial guess x (resized to b's size and zeroed if its size differs).
  Result solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
               int max_iterations) const;

 private:
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;  // y = A x
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  std::unique_ptr<base::ThreadPool> m_pool;
  RowMatrix m_full;
  // For each value of the lower triangle, its position in m_full, and the position of its
  // mirror (−1 on the diagonal).
  std::vector<int> m_to_full, m_to_mirror;
  std::vector<int> m_block_positions;             // per vertex, its 3×3 diagonal block in m_full
  std::vector<Eigen::Matrix3d> m_block_inverse;  // per vertex
};

}  // namespace weft::sim
