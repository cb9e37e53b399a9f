// Conjugate gradients with a 3×3 block-Jacobi preconditioner (sim/linear/block_conjugate_gradient.h)
// against a direct solve, its stopping rule, its determinism across threads, and a breakdown.
#include "sim/linear/block_conjugate_gradient.h"

#include <gtest/gtest.h>

#include <memory>

#include <Eigen/SparseCholesky>

#include "tests/support/block_grid_matrix.h"

namespace weft::sim {
namespace {

using test_matrices::grid_system;
using test_matrices::random_vector;

SparseMatrix lower(const SparseMatrix& full) { return test_matrices::lower_triangle(full); }

// Conjugate gradients analysed and set up for the full symmetric matrix A.
std::unique_ptr<BlockConjugateGradient> prepared(const SparseMatrix& A, int threads = 1) {
  auto cg = std::make_unique<BlockConjugateGradient>(threads);
  cg->analyze(lower(A));
  cg->set_matrix(lower(A));
  return cg;
}

TEST(BlockConjugateGradient, ReachesTheToleranceAndAgreesWithADirectSolve) {
  const SparseMatrix A = grid_system(12, 0.05, 1);
  const Eigen::VectorXd b = random_vector(A.rows(), 2);
  const auto cg = prepared(A);
  Eigen::VectorXd x;
  const BlockConjugateGradient::Result r = cg->solve(b, x, 1e-10, 2000);
  EXPECT_FALSE(r.breakdown);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LE(r.relative_residual, 1e-10);
  EXPECT_NEAR((b - A * x).norm() / b.norm(), r.relative_residual, 1e-12);
  const Eigen::SimplicialLDLT<SparseMatrix> direct(A);
  const Eigen::VectorXd exact = direct.solve(b);
  EXPECT_LT((x - exact).norm() / exact.norm(), 1e-7);
}

// Stops at the first iterate with ‖b − A x‖ ≤ tol ‖b‖; a guess that already meets it costs none.
TEST(BlockConjugateGradient, StopsAtTheToleranceAndKeepsAGoodGuess) {
  const SparseMatrix A = grid_system(10, 0.05, 3);
  const Eigen::VectorXd b = random_vector(A.rows(), 4);
  const auto cg = prepared(A);
  Eigen::VectorXd x;
  const auto loose = cg->solve(b, x, 1e-3, 2000);
  EXPECT_LE(loose.relative_residual, 1e-3);
  Eigen::VectorXd y;
  const auto one_less = cg->solve(b, y, 1e-3, loose.iterations - 1);
  EXPECT_GT(one_less.relative_residual, 1e-3);
  const auto again = cg->solve(b, x, 1e-3, 2000);
  EXPECT_EQ(again.iterations, 0);
}

// The block-Jacobi preconditioner is exact on a block-diagonal matrix: one iteration.
TEST(BlockConjugateGradient, BlockDiagonalMatrixTakesOneIteration) {
  const SparseMatrix A = grid_system(1, 0.5, 5);  // one vertex: a single 3×3 block
  const auto cg = prepared(A);
  Eigen::VectorXd x;
  const auto r = cg->solve(Eigen::Vector3d(1.0, -2.0, 0.5), x, 1e-12, 10);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LE(r.relative_residual, 1e-12);
}

// Rows are shared among threads; each row is one sequential sum, so 1, 2 and 3 threads give the
// same bits.
TEST(BlockConjugateGradient, SameBitsForAnyNumberOfThreads) {
  const SparseMatrix A = grid_system(40, 0.05, 6);  // 4800 rows: two shares
  const Eigen::VectorXd b = random_vector(A.rows(), 7);
  Eigen::VectorXd x[3];
  for (int threads = 1; threads <= 3; ++threads) {
    prepared(A, threads)->solve(b, x[threads - 1], 1e-8, 500);
  }
  EXPECT_TRUE((x[0].array() == x[1].array()).all());
  EXPECT_TRUE((x[0].array() == x[2].array()).all());
}

// The product sums each block row in the scalar order the header states — its diagonal block,
// then its other blocks by column, each block row as (a_r0 x_0 + a_r1 x_1) + a_r2 x_2 — to the
// bit, whichever of its builds (AVX2 or the baseline) this machine runs: results do not depend
// on the processor's vector width.
TEST(BlockConjugateGradient, ProductIsTheScalarSumToTheBit) {
  const SparseMatrix A = grid_system(9, 0.05, 9);
  const Eigen::VectorXd x = random_vector(A.rows(), 10);
  const auto cg = prepared(A);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(A.rows());
  cg->multiply(x, y);
  // The matrix conjugate gradients hold: A's lower triangle and its mirror (A itself may be
  // asymmetric in its last bits).
  const SparseMatrix held = lower(A).selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd dense(held);
  const Eigen::Index blocks = A.rows() / 3;
  const auto block_row_sum = [&](Eigen::Index p, Eigen::Index q, int r) {
    const Eigen::Index i = 3 * p + r, j = 3 * q;
    return (dense(i, j) * x[j] + dense(i, j + 1) * x[j + 1]) + dense(i, j + 2) * x[j + 2];
  };
  for (Eigen::Index p = 0; p < blocks; ++p)
    for (int r = 0; r < 3; ++r) {
      double sum = block_row_sum(p, p, r);
      for (Eigen::Index q = 0; q < blocks; ++q)
        if (q != p && dense.block<3, 3>(3 * p, 3 * q).any()) sum += block_row_sum(p, q, r);
      ASSERT_EQ(y[3 * p + r], sum) << "row " << 3 * p + r;
    }
}

TEST(BlockConjugateGradient, IndefiniteMatrixIsABreakdown) {
  SparseMatrix A = grid_system(4, 0.05, 8);
  A.coeffRef(6, 6) = -50.0;  // a negative diagonal entry: not positive definite
  const auto cg = prepared(A);
  Eigen::VectorXd x;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(A.rows());
  b[6] = 1.0;
  EXPECT_TRUE(cg->solve(b, x, 1e-10, 200).breakdown);
}

}  // namespace
}  // namespace weft::sim
