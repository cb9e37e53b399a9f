#include "sim/linear/block_conjugate_gradient.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/check.h"

namespace weft::sim {
namespace {

// Block rows below which one thread multiplies alone: waking the pool costs more than it saves.
constexpr std::size_t kBlockRowsPerThreadMin = 700;

}  // namespace

BlockConjugateGradient::BlockConjugateGradient(int threads)
    : m_pool(std::make_unique<base::ThreadPool>(threads)) {}

BlockConjugateGradient::~BlockConjugateGradient() = default;

void BlockConjugateGradient::analyze(const SparseMatrix& lower) {
  WEFT_CHECK(
      lower.rows() == lower.cols() && lower.rows() % 3 == 0 && lower.isCompressed(),
      "BlockConjugateGradient::analyze: expected a compressed square matrix of 3k rows, got " +
          std::to_string(lower.rows()) + "x" + std::to_string(lower.cols()));
  const int blocks = static_cast<int>(lower.rows() / 3);
  // The 3×3 blocks with an entry, in either triangle, and every diagonal block.
  std::vector<std::vector<int>> columns(static_cast<std::size_t>(blocks));
  for (int p = 0; p < blocks; ++p) columns[static_cast<std::size_t>(p)].push_back(p);
  for (int col = 0; col < lower.cols(); ++col)
    for (int k = lower.outerIndexPtr()[col]; k < lower.outerIndexPtr()[col + 1]; ++k) {
      const int p = lower.innerIndexPtr()[k] / 3, q = col / 3;
      columns[static_cast<std::size_t>(p)].push_back(q);
      columns[static_cast<std::size_t>(q)].push_back(p);
    }
  m_block_start.assign(1, 0);
  m_block_column.clear();
  for (std::vector<int>& row : columns) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    m_block_column.insert(m_block_column.end(), row.begin(), row.end());
    m_block_start.push_back(static_cast<int>(m_block_column.size()));
  }
  m_blocks.assign(9 * m_block_column.size(), 0.0);
  // Where entry (row, col) lives in m_blocks (row-major within its block).
  const auto position = [&](int row, int col) {
    const int p = row / 3, q = col / 3;
    const auto begin = m_block_column.begin() + m_block_start[static_cast<std::size_t>(p)];
    const auto end = m_block_column.begin() + m_block_start[static_cast<std::size_t>(p) + 1];
    const auto block = std::lower_bound(begin, end, q) - m_block_column.begin();
    return static_cast<int>(9 * block + 3 * (row % 3) + col % 3);
  };
  m_to_block.assign(static_cast<std::size_t>(lower.nonZeros()), -1);
  m_to_mirror.assign(static_cast<std::size_t>(lower.nonZeros()), -1);
  for (int col = 0; col < lower.cols(); ++col)
    for (int k = lower.outerIndexPtr()[col]; k < lower.outerIndexPtr()[col + 1]; ++k) {
      const int row = lower.innerIndexPtr()[k];
      m_to_block[static_cast<std::size_t>(k)] = position(row, col);
      if (row != col) m_to_mirror[static_cast<std::size_t>(k)] = position(col, row);
    }
  m_diagonal_block.resize(static_cast<std::size_t>(blocks));
  for (int p = 0; p < blocks; ++p) m_diagonal_block[static_cast<std::size_t>(p)] = position(3 * p, 3 * p);
  m_block_inverse.assign(static_cast<std::size_t>(blocks), Eigen::Matrix3d::Identity());
}

void BlockConjugateGradient::set_matrix(const SparseMatrix& lower) {
  WEFT_CHECK(lower.nonZeros() == static_cast<Eigen::Index>(m_to_block.size()) &&
                 lower.rows() == 3 * static_cast<Eigen::Index>(m_diagonal_block.size()),
             "BlockConjugateGradient::set_matrix: not the analysed pattern");
  std::fill(m_blocks.begin(), m_blocks.end(), 0.0);
  const double* values = lower.valuePtr();
  for (std::size_t k = 0; k < m_to_block.size(); ++k) {
    m_blocks[static_cast<std::size_t>(m_to_block[k])] = values[k];
    if (m_to_mirror[k] >= 0) m_blocks[static_cast<std::size_t>(m_to_mirror[k])] = values[k];
  }
  for (std::size_t p = 0; p < m_block_inverse.size(); ++p)
    m_block_inverse[p] = Block(m_blocks.data() + m_diagonal_block[p]).inverse();
}

void BlockConjugateGradient::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const std::size_t blocks = m_diagonal_block.size();
  const std::size_t shares =
      std::clamp<std::size_t>(blocks / kBlockRowsPerThreadMin, 1, m_pool->size());
  const auto block_rows_of = [&](std::size_t share) {
    const std::size_t begin = base::share_begin(blocks, shares, share);
    const std::size_t end = base::share_begin(blocks, shares, share + 1);
    for (std::size_t p = begin; p < end; ++p) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = m_block_start[p]; k < m_block_start[p + 1]; ++k)
        sum.noalias() += Block(m_blocks.data() + 9 * k) *
                         x.segment<3>(3 * static_cast<Eigen::Index>(m_block_column[static_cast<std::size_t>(k)]));
      y.segment<3>(3 * static_cast<Eigen::Index>(p)) = sum;
    }
  };
  if (shares == 1) {
    block_rows_of(0);
  } else {
    m_pool->run(shares, block_rows_of);
  }
}

void BlockConjugateGradient::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  for (std::size_t v = 0; v < m_block_inverse.size(); ++v) {
    const auto i = static_cast<Eigen::Index>(3 * v);
    z.segment<3>(i).noalias() = m_block_inverse[v] * r.segment<3>(i);
  }
}

BlockConjugateGradient::Result BlockConjugateGradient::solve(const Eigen::VectorXd& b,
                                                             Eigen::VectorXd& x, double tolerance,
                                                             int max_iterations) const {
  WEFT_CHECK(b.size() == 3 * static_cast<Eigen::Index>(m_diagonal_block.size()),
             "BlockConjugateGradient::solve: right-hand side has " + std::to_string(b.size()) +
                 " rows, expected " + std::to_string(3 * m_diagonal_block.size()));
  Result result;
  if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
  const double b_norm2 = b.squaredNorm();
  if (!std::isfinite(b_norm2)) {
    result.breakdown = true;
    return result;
  }
  if (b_norm2 == 0.0) {
    x.setZero();
    return result;
  }
  const double threshold = tolerance * tolerance * b_norm2;
  Eigen::VectorXd r(b.size()), z(b.size()), p(b.size()), q(b.size());
  multiply(x, q);
  r = b - q;
  double r_norm2 = r.squaredNorm();
  if (!std::isfinite(r_norm2)) {  // a non-finite matrix entry or guess
    result.breakdown = true;
    return result;
  }
  if (r_norm2 > threshold) {
    precondition(r, z);
    p = z;
    double rz = r.dot(z);
    while (result.iterations < max_iterations) {
      if (!(rz > 0.0)) {
        result.breakdown = true;
        break;
      }
      multiply(p, q);
      const double curvature = p.dot(q);
      if (!(curvature > 0.0)) {
        result.breakdown = true;
        break;
      }
      ++result.iterations;
      const double alpha = rz / curvature;
      x += alpha * p;
      r -= alpha * q;
      r_norm2 = r.squaredNorm();
      if (r_norm2 <= threshold) break;
      precondition(r, z);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
  }
  result.relative_residual = std::sqrt(r_norm2 / b_norm2);
  return result;
}

}  // namespace weft::sim
