#include "sim/linear/block_sparse_matrix.h"

#include <algorithm>
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
  m_values.assign(9 * m_column.size(), 0.0);
  m_diagonal.assign(9 * columns.size(), 0.0);
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

void BlockSparseMatrix::multiply_rows(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                                      std::size_t begin, std::size_t end) const {
  const double* xs = x.data();
  double* ys = y.data();
  for (std::size_t p = begin; p < end; ++p) {
    const double* d = diagonal(p);
    const double* xp = xs + 3 * p;
    double y0 = d[0] * xp[0] + d[1] * xp[1] + d[2] * xp[2];
    double y1 = d[3] * xp[0] + d[4] * xp[1] + d[5] * xp[2];
    double y2 = d[6] * xp[0] + d[7] * xp[1] + d[8] * xp[2];
    for (int k = m_start[p]; k < m_start[p + 1]; ++k) {
      const double* a = off_diagonal(k);
      const double* xq = xs + 3 * static_cast<std::size_t>(m_column[static_cast<std::size_t>(k)]);
      y0 += a[0] * xq[0] + a[1] * xq[1] + a[2] * xq[2];
      y1 += a[3] * xq[0] + a[4] * xq[1] + a[5] * xq[2];
      y2 += a[6] * xq[0] + a[7] * xq[1] + a[8] * xq[2];
    }
    ys[3 * p] = y0;
    ys[3 * p + 1] = y1;
    ys[3 * p + 2] = y2;
  }
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
  for (std::size_t p = 0; p < inverse.size(); ++p)
    inverse[p] = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(diagonal(p)).inverse();
}

Eigen::MatrixXd BlockSparseMatrix::to_dense() const {
  using Block = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
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
  return (m_values.size() + m_diagonal.size()) * sizeof(double) +
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
