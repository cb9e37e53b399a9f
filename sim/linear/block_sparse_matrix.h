#pragma once
// A symmetric matrix of 3×3 blocks, both triangles stored: the diagonal block of each block row
// apart, then its off-diagonal blocks in block compressed rows (one column index per 9 values,
// column-major within a block: the product adds a block's three columns as vectors). The form
// of implicit Euler's 3#V system that conjugate gradients (block_conjugate_gradient.h) and its
// multigrid (grid_multigrid.h) multiply.
//
// y = A x sums every block row in one fixed order (its diagonal block, then its other blocks by
// column), so the product is the same bits however its rows are shared among threads. A product
// streams every block once: its storage is its cost (bench/memory_bandwidth_bench.cpp).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "base/thread_pool.h"
#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim {

class BlockSparseMatrix {
 public:
  BlockSparseMatrix() = default;
  // Zero blocks on the given pattern: columns[p] lists block row p's off-diagonal block columns
  // (sorted, unique, none equal to p).
  explicit BlockSparseMatrix(const std::vector<std::vector<int>>& columns);

  std::size_t block_rows() const { return m_start.size() - 1; }
  std::size_t off_diagonal_blocks() const { return m_column.size(); }
  const std::vector<int>& row_start() const { return m_start; }
  const std::vector<int>& column() const { return m_column; }
  // Block row p's off-diagonal columns, [begin, end) into column() and the off-diagonal values.
  int begin(std::size_t p) const { return m_start[p]; }
  int end(std::size_t p) const { return m_start[p + 1]; }
  // The index of off-diagonal block (p, q) among the off-diagonal blocks, −1 if not stored.
  int find(int p, int q) const;

  double* diagonal(std::size_t p) { return m_diagonal.data() + 9 * p; }
  const double* diagonal(std::size_t p) const { return m_diagonal.data() + 9 * p; }
  double* off_diagonal(int k) { return m_values.data() + 9 * static_cast<std::size_t>(k); }
  const double* off_diagonal(int k) const { return m_values.data() + 9 * static_cast<std::size_t>(k); }
  void set_zero();

  // y = A x for block rows [begin, end) (y sized like x beforehand).
  void multiply_rows(const Eigen::VectorXd& x, Eigen::VectorXd& y, std::size_t begin,
                     std::size_t end) const;
  // y = A x, the block rows shared among `pool`'s threads when there are enough of them.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y, base::ThreadPool* pool) const;
  // The inverse of every diagonal block.
  void invert_diagonal(std::vector<Eigen::Matrix3d>& inverse) const;
  // The whole matrix, dense (for small matrices: the multigrid's coarsest level, tests).
  Eigen::MatrixXd to_dense() const;
  // Bytes one product streams at the least: every block and index once, x and y once.
  std::size_t bytes_per_product() const;

 private:
  std::vector<int> m_start{0}, m_column;
  // 9 per block, and one padding value after the last: the product reads a column as four
  // doubles.
  std::vector<double> m_values;    // the off-diagonal blocks
  std::vector<double> m_diagonal;  // one block per block row
};

// The block pattern of `lower` (a compressed lower triangle of 3k rows, as SparseSpdSolver
// takes it): for each block row, its off-diagonal block columns in either triangle.
std::vector<std::vector<int>> block_pattern(const SparseMatrix& lower);

}  // namespace weft::sim
