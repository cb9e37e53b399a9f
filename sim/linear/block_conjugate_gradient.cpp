#include "sim/linear/block_conjugate_gradient.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::sim {
namespace {

// Rows below which one thread multiplies alone: waking the pool costs more than it saves.
constexpr Eigen::Index kRowsPerThreadMin = 2048;

// Position of (row, col) in a compressed row-major matrix's value array; the entry must exist.
int position_of(const Eigen::SparseMatrix<double, Eigen::RowMajor, int>& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[row];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[row + 1];
  const int* it = std::lower_bound(begin, end, col);
  if (it == end || *it != col)
    throw std::logic_error("BlockConjugateGradient: entry (" + std::to_string(row) + ", " +
                           std::to_string(col) + ") is not in the pattern");
  return static_cast<int>(it - m.innerIndexPtr());
}

}  // namespace

BlockConjugateGradient::BlockConjugateGradient(int threads)
    : m_pool(std::make_unique<base::ThreadPool>(threads)) {}

BlockConjugateGradient::~BlockConjugateGradient() = default;

void BlockConjugateGradient::analyze(const SparseMatrix& lower) {
  if (lower.rows() != lower.cols() || lower.rows() % 3 != 0 || !lower.isCompressed())
    throw std::logic_error("BlockConjugateGradient::analyze: expected a compressed square matrix "
                           "of 3k rows, got " + std::to_string(lower.rows()) + "x" +
                           std::to_string(lower.cols()));
  const int n = static_cast<int>(lower.rows());
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(2 * static_cast<std::size_t>(lower.nonZeros()));
  for (int col = 0; col < n; ++col)
    for (int k = lower.outerIndexPtr()[col]; k < lower.outerIndexPtr()[col + 1]; ++k) {
      const int row = lower.innerIndexPtr()[k];
      entries.emplace_back(row, col, 0.0);
      if (row != col) entries.emplace_back(col, row, 0.0);
    }
  // Every diagonal block complete, so that it can be inverted.
  for (int v = 0; v < n / 3; ++v)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * v + r, 3 * v + c, 0.0);
  m_full.resize(n, n);
  m_full.setFromTriplets(entries.begin(), entries.end());
  m_full.makeCompressed();

  m_to_full.assign(static_cast<std::size_t>(lower.nonZeros()), -1);
  m_to_mirror.assign(static_cast<std::size_t>(lower.nonZeros()), -1);
  for (int col = 0; col < n; ++col)
    for (int k = lower.outerIndexPtr()[col]; k < lower.outerIndexPtr()[col + 1]; ++k) {
      const int row = lower.innerIndexPtr()[k];
      m_to_full[static_cast<std::size_t>(k)] = position_of(m_full, row, col);
      if (row != col) m_to_mirror[static_cast<std::size_t>(k)] = position_of(m_full, col, row);
    }
  m_block_inverse.assign(static_cast<std::size_t>(n / 3), Eigen::Matrix3d::Identity());
  m_block_positions.clear();
  for (int v = 0; v < n / 3; ++v)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m_block_positions.push_back(position_of(m_full, 3 * v + r, 3 * v + c));
}

void BlockConjugateGradient::set_matrix(const SparseMatrix& lower) {
  if (lower.nonZeros() != static_cast<Eigen::Index>(m_to_full.size()) ||
      lower.rows() != m_full.rows())
    throw std::logic_error("BlockConjugateGradient::set_matrix: not the analysed pattern");
  double* full = m_full.valuePtr();
  std::fill(full, full + m_full.nonZeros(), 0.0);
  const double* values = lower.valuePtr();
  for (std::size_t k = 0; k < m_to_full.size(); ++k) {
    full[m_to_full[k]] = values[k];
    if (m_to_mirror[k] >= 0) full[m_to_mirror[k]] = values[k];
  }
  for (std::size_t v = 0; v < m_block_inverse.size(); ++v) {
    Eigen::Matrix3d block;
    for (int k = 0; k < 9; ++k) block(k / 3, k % 3) = full[m_block_positions[9 * v + static_cast<std::size_t>(k)]];
    m_block_inverse[v] = block.inverse();
  }
}

void BlockConjugateGradient::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::Index rows = m_full.rows();
  const std::size_t shares =
      std::min<std::size_t>(m_pool->size(), static_cast<std::size_t>(std::max<Eigen::Index>(1, rows / kRowsPerThreadMin)));
  const int* outer = m_full.outerIndexPtr();
  const int* inner = m_full.innerIndexPtr();
  const double* values = m_full.valuePtr();
  const auto rows_of = [&](std::size_t share) {
    const auto begin = static_cast<Eigen::Index>(base::share_begin(static_cast<std::size_t>(rows), shares, share));
    const auto end = static_cast<Eigen::Index>(base::share_begin(static_cast<std::size_t>(rows), shares, share + 1));
    for (Eigen::Index i = begin; i < end; ++i) {
      double sum = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) sum += values[k] * x[inner[k]];
      y[i] = sum;
    }
  };
  if (shares == 1) {
    rows_of(0);
  } else {
    m_pool->run(shares, rows_of);
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
  if (b.size() != m_full.rows())
    throw std::logic_error("BlockConjugateGradient::solve: right-hand side has " +
                           std::to_string(b.size()) + " rows, expected " +
                           std::to_string(m_full.rows()));
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
