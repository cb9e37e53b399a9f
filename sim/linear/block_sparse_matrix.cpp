#include "sim/linear/block_sparse_matrix.h"

#include <algorithm>
#include <cstring>
#include <string>

#include <Eigen/LU>

#include "base/check.h"

namespace weft::sim {
namespace {

// Block rows below which one thread multiplies alone: waking the pool costs more than it saves.
constexpr std::size_t kBlockRowsPerThreadMin = 700;

}  // namespace

BlockSparseMatrix::BlockSparseMatrix(const std::vector<std::vector<int>>& columns) {
  for (std::size_t p = 0; p < columns.size(); ++p) {
    m_column.insert(m_column.end(), columns[p].begin(), columns[p].end());
    m_start.push_back(static_cast<int>(m_column.size()));
  }
  m_values.assign(9 * m_column.size() + 1, 0.0);
  m_diagonal.assign(9 * columns.size() + 1, 0.0);
}

int BlockSparseMatrix::find(int p, int q) const {
  const auto first = m_column.begin() + m_start[static_cast<std::size_t>(p)];
  const auto last = m_column.begin() + m_start[static_cast<std::size_t>(p) + 1];
  const auto it = std::lower_bound(first, last, q);
  return it != last && *it == q ? static_cast<int>(it - m_column.begin()) : -1;
}

void BlockSparseMatrix::set_zero() {
  std::fill(m_values.begin(), m_values.end(), 0.0);
  std::fill(m_diagonal.begin(), m_diagonal.end(), 0.0);
}

namespace {

// Four doubles; the fourth lane carries a value nobody reads.
typedef double Lanes __attribute__((vector_size(32)));

// product = the column-major 3×3 block a times x, as (a_0 x_0 + a_1 x_1) + a_2 x_2, a_j its
// columns, each read as four doubles (the fourth is the next column's first, or the storage's
// padding). Always inlined into the product's clones; the vector is passed by reference, never
// returned, as compilers warn (GCC) or refuse (Clang) where the baseline and AVX would pass it
// differently.
[[gnu::always_inline]] inline void block_times(const double* a, const double* x, Lanes& product) {
  Lanes c0, c1, c2;
  std::memcpy(&c0, a, sizeof c0);
  std::memcpy(&c1, a + 3, sizeof c1);
  std::memcpy(&c2, a + 6, sizeof c2);
  product = (c0 * x[0] + c1 * x[1]) + c2 * x[2];
}

// y_p = Σ_k A_pk x_k for block rows [begin, end): each block's three columns scaled by x's three
// components, column 0 plus column 1, plus column 2, then added to the row's sum — row r of the
// block in the order (a_r0 x_0 + a_r1 x_1) + a_r2 x_2 of the scalar sum, in three lanes at once.
// Built for AVX2 and for the baseline; neither contracts to FMA, so both give the same bits.
__attribute__((target_clones("avx2", "default"))) void multiply_block_rows(
    const double* diagonal, const double* values, const int* start, const int* column,
    const double* x, double* y, std::size_t begin, std::size_t end) {
  for (std::size_t p = begin; p < end; ++p) {
    const double* d = diagonal + 9 * p;
    const double* xp = x + 3 * p;
    Lanes sum, product;
    block_times(d, xp, sum);
    for (int k = start[p]; k < start[p + 1]; ++k) {
      block_times(values + 9 * static_cast<std::size_t>(k),
                  x + 3 * static_cast<std::size_t>(column[k]), product);
      sum += product;
    }
    y[3 * p] = sum[0];
    y[3 * p + 1] = sum[1];
    y[3 * p + 2] = sum[2];
  }
}

}  // namespace

void BlockSparseMatrix::multiply_rows(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                                      std::size_t begin, std::size_t end) const {
  multiply_block_rows(m_diagonal.data(), m_values.data(), m_start.data(), m_column.data(), x.data(),
                      y.data(), begin, end);
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                                 base::ThreadPool* pool) const {
  const std::size_t rows = block_rows();
  const std::size_t shares =
      pool ? std::clamp<std::size_t>(rows / kBlockRowsPerThreadMin, 1, pool->size()) : 1;
  if (shares == 1) {
    multiply_rows(x, y, 0, rows);
    return;
  }
  pool->run(shares, [&](std::size_t share) {
    multiply_rows(x, y, base::share_begin(rows, shares, share),
                  base::share_begin(rows, shares, share + 1));
  });
}

void BlockSparseMatrix::invert_diagonal(std::vector<Eigen::Matrix3d>& inverse) const {
  inverse.resize(block_rows());
  // Through a row-major copy: Eigen's 3×3 inverse rounds differently by storage order, and
  // this order is the one the blocks had before they were stored column-major.
  for (std::size_t p = 0; p < inverse.size(); ++p) {
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> block =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::ColMajor>>(diagonal(p));
    inverse[p] = block.inverse();
  }
}

Eigen::MatrixXd BlockSparseMatrix::to_dense() const {
  using Block = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::ColMajor>>;
  const auto n = static_cast<Eigen::Index>(3 * block_rows());
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t p = 0; p < block_rows(); ++p) {
    const auto r = static_cast<Eigen::Index>(3 * p);
    dense.block<3, 3>(r, r) = Block(diagonal(p));
    for (int k = begin(p); k < end(p); ++k)
      dense.block<3, 3>(r, 3 * static_cast<Eigen::Index>(m_column[static_cast<std::size_t>(k)])) =
          Block(off_diagonal(k));
  }
  return dense;
}

std::size_t BlockSparseMatrix::bytes_per_product() const {
  return 9 * (m_column.size() + block_rows()) * sizeof(double) +
         (m_column.size() + m_start.size()) * sizeof(int) + 2 * 3 * block_rows() * sizeof(double);
}

std::vector<std::vector<int>> block_pattern(const SparseMatrix& lower) {
  WEFT_CHECK(lower.rows() == lower.cols() && lower.rows() % 3 == 0 && lower.isCompressed(),
             "block_pattern: expected a compressed square matrix of 3k rows, got " +
                 std::to_string(lower.rows()) + "x" + std::to_string(lower.cols()));
  std::vector<std::vector<int>> columns(static_cast<std::size_t>(lower.rows() / 3));
  for (int col = 0; col < lower.cols(); ++col)
    for (int k = lower.outerIndexPtr()[col]; k < lower.outerIndexPtr()[col + 1]; ++k) {
      const int p = lower.innerIndexPtr()[k] / 3, q = col / 3;
      if (p == q) continue;
      columns[static_cast<std::size_t>(p)].push_back(q);
      columns[static_cast<std::size_t>(q)].push_back(p);
    }
  for (std::vector<int>& row : columns) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  }
  return columns;
}

}  // namespace weft::sim
