#include "sim/linear/block_conjugate_gradient.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/check.h"

namespace weft::sim {

BlockConjugateGradient::BlockConjugateGradient(int threads)
    : m_pool(std::make_unique<base::ThreadPool>(threads)) {}

BlockConjugateGradient::~BlockConjugateGradient() = default;

void BlockConjugateGradient::analyze(const SparseMatrix& lower, Index grid_nu, Index grid_nv,
                                     GridPreconditioner grid) {
  m_matrix = BlockSparseMatrix(block_pattern(lower));
  m_source = Sources{};
  m_source.nonzeros = lower.nonZeros();
  m_source.diagonal.assign(9 * m_matrix.block_rows(), -1);
  m_source.off_diagonal.assign(9 * m_matrix.off_diagonal_blocks(), -1);
  for (int col = 0; col < lower.cols(); ++col)
    for (int k = lower.outerIndexPtr()[col]; k < lower.outerIndexPtr()[col + 1]; ++k) {
      const int row = lower.innerIndexPtr()[k];
      m_source.at(m_matrix, row, col) = k;
      m_source.at(m_matrix, col, row) = k;
    }
  m_block_inverse.assign(m_matrix.block_rows(), Eigen::Matrix3d::Identity());
  m_multigrid.reset();
  m_line.reset();
  m_line_ok = false;
  m_line_when_slow = grid == GridPreconditioner::lines_when_slow;
  if (grid_nu > 0 && grid_nv > 0 && grid != GridPreconditioner::multigrid) {
    m_line = std::make_unique<GridLinePreconditioner>(m_matrix, grid_nu, grid_nv);
  } else if (grid_nu > 0 && grid_nv > 0) {
    if (std::optional<GridMultigrid> mg = GridMultigrid::make(m_matrix, grid_nu, grid_nv))
      m_multigrid = std::make_unique<GridMultigrid>(std::move(*mg));
  }
}

// Entry (row, col) of the block matrix, column-major within its block.
int& BlockConjugateGradient::Sources::at(const BlockSparseMatrix& matrix, int row, int col) {
  const int p = row / 3, q = col / 3;
  const auto within = static_cast<std::size_t>(3 * (col % 3) + row % 3);
  if (p == q) return diagonal[9 * static_cast<std::size_t>(p) + within];
  return off_diagonal[9 * static_cast<std::size_t>(matrix.find(p, q)) + within];
}

// Each stored value read from its source in `lower`, in storage order (a gather: the writes
// stream; a value without a source — off the diagonal of a held vertex's identity block — is
// 0).
void BlockConjugateGradient::set_matrix(const SparseMatrix& lower) {
  WEFT_CHECK(lower.nonZeros() == m_source.nonzeros &&
                 lower.rows() == 3 * static_cast<Eigen::Index>(m_block_inverse.size()),
             "BlockConjugateGradient::set_matrix: not the analysed pattern");
  const double* values = lower.valuePtr();
  const auto gather = [values](const std::vector<int>& from, double* to) {
    for (std::size_t j = 0; j < from.size(); ++j) to[j] = from[j] >= 0 ? values[from[j]] : 0.0;
  };
  gather(m_source.diagonal, m_matrix.diagonal(0));
  if (m_matrix.off_diagonal_blocks() > 0) gather(m_source.off_diagonal, m_matrix.off_diagonal(0));
  // The line solves, where they can be factored, take the place of block Jacobi, whose
  // inverses are then not needed; with lines_when_slow, solve() sets them up when it needs them.
  m_line_ok = false;
  m_line_current = false;
  if (m_line && !m_line_when_slow) m_line_ok = m_line->update(m_matrix);
  if (!m_line_ok) m_matrix.invert_diagonal(m_block_inverse);
  if (m_multigrid) m_multigrid->update(m_matrix);
}

void BlockConjugateGradient::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  m_matrix.multiply(x, y, m_pool.get());
}

int BlockConjugateGradient::multigrid_levels() const {
  return m_multigrid ? m_multigrid->levels() : 0;
}

void BlockConjugateGradient::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z,
                                          Preconditioner which) const {
  if (which == Preconditioner::multigrid) {
    m_multigrid->apply(m_matrix, m_block_inverse, r, z, m_pool.get());
    return;
  }
  if (which == Preconditioner::lines) {
    m_line->apply(r, z);
    return;
  }
  for (std::size_t v = 0; v < m_block_inverse.size(); ++v) {
    const auto i = static_cast<Eigen::Index>(3 * v);
    z.segment<3>(i).noalias() = m_block_inverse[v] * r.segment<3>(i);
  }
}

BlockConjugateGradient::Result BlockConjugateGradient::solve(const Eigen::VectorXd& b,
                                                             Eigen::VectorXd& x, double tolerance,
                                                             int max_iterations) {
  WEFT_CHECK(b.size() == 3 * static_cast<Eigen::Index>(m_block_inverse.size()),
             "BlockConjugateGradient::solve: right-hand side has " + std::to_string(b.size()) +
                 " rows, expected " + std::to_string(3 * m_block_inverse.size()));
  if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
  if (m_line && m_line_when_slow) {
    const Iteration probe =
        iterate(b, x, tolerance, max_iterations, Preconditioner::block_jacobi, kProbeIterations);
    if (!probe.slow) return probe.result;
    if (!m_line_current) {
      m_line_ok = m_line->update(m_matrix);
      m_line_current = true;
    }
    Result rest = iterate(b, x, tolerance, max_iterations - probe.result.iterations,
                          m_line_ok ? Preconditioner::lines : Preconditioner::block_jacobi)
                      .result;
    rest.iterations += probe.result.iterations;
    return rest;
  }
  if (m_line_ok) return iterate(b, x, tolerance, max_iterations, Preconditioner::lines).result;
  if (!m_multigrid)
    return iterate(b, x, tolerance, max_iterations, Preconditioner::block_jacobi).result;
  const Eigen::VectorXd guess = x;
  const Result result = iterate(b, x, tolerance, max_iterations, Preconditioner::multigrid).result;
  if (!result.breakdown) return result;
  x = guess;  // the cycle was not positive definite for this matrix: block Jacobi instead
  return iterate(b, x, tolerance, max_iterations, Preconditioner::block_jacobi).result;
}

BlockConjugateGradient::Iteration BlockConjugateGradient::iterate(
    const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance, int max_iterations,
    Preconditioner preconditioner, int probe) const {
  Iteration out;
  Result& result = out.result;
  const double b_norm2 = b.squaredNorm();
  if (!std::isfinite(b_norm2)) {
    result.breakdown = true;
    return out;
  }
  if (b_norm2 == 0.0) {
    x.setZero();
    return out;
  }
  const double threshold = tolerance * tolerance * b_norm2;
  Eigen::VectorXd r(b.size()), z(b.size()), p(b.size()), q(b.size());
  multiply(x, q);
  r = b - q;
  double r_norm2 = r.squaredNorm();
  if (!std::isfinite(r_norm2)) {  // a non-finite matrix entry or guess
    result.breakdown = true;
    return out;
  }
  const double start_norm2 = r_norm2;
  if (r_norm2 > threshold) {
    precondition(r, z, preconditioner);
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
      if (result.iterations == probe && slow(start_norm2, r_norm2, threshold, probe)) {
        out.slow = true;
        break;
      }
      precondition(r, z, preconditioner);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
  }
  result.relative_residual = std::sqrt(r_norm2 / b_norm2);
  return out;
}

// Whether the mean rate of decrease of the residual's norm over the first `done` iterations,
// from start_norm2 to now_norm2 (squared norms), would take more than kSlowIterations in all to
// reach threshold (a squared norm).
bool BlockConjugateGradient::slow(double start_norm2, double now_norm2, double threshold,
                                  int done) {
  const double rate = std::log(now_norm2 / start_norm2) / done;  // < 0 where it decreases
  if (!(rate < 0.0)) return true;
  return done + std::log(threshold / now_norm2) / rate > kSlowIterations;
}

}  // namespace weft::sim
