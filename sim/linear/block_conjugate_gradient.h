#pragma once
// Conjugate gradients for implicit Euler's 3#V system (sim/integrators/implicit_euler.h), with
// a 3×3 block-Jacobi preconditioner (the inverse of each vertex's diagonal block) and the
// matrix–vector product shared among threads.
//
// The system arrives as SparseSpdSolver takes it: the lower triangle, column-major. analyze()
// builds a full (both triangles) copy of its pattern in 3×3 blocks (block compressed rows: one
// column index per 9 values) once; set_matrix() scatters the values into it. Each thread
// multiplies a contiguous range of block rows, and every block row is summed in one fixed
// order, so the product — and with the sequential vector updates and dot products, every
// iterate — is the same bits for any number of threads.
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
  using Block = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;  // y = A x
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  std::unique_ptr<base::ThreadPool> m_pool;
  // Block compressed rows: block row p has the blocks m_block_start[p] … m_block_start[p+1]−1,
  // in block columns m_block_column[…], their values 9 each (row-major) in m_blocks.
  std::vector<int> m_block_start, m_block_column;
  std::vector<double> m_blocks;
  // For each value of the lower triangle, its index in m_blocks, and its mirror's (−1 on the
  // diagonal).
  std::vector<int> m_to_block, m_to_mirror;
  std::vector<int> m_diagonal_block;             // per vertex, its diagonal block's index in m_blocks
  std::vector<Eigen::Matrix3d> m_block_inverse;  // per vertex
};

}  // namespace weft::sim
