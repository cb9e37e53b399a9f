// Conjugate gradients with a 3×3 block-Jacobi preconditioner (sim/linear/block_conjugate_gradient.h)
// against a direct solve, its stopping rule, its determinism across threads, and a breakdown.
#include "sim/linear/block_conjugate_gradient.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include <Eigen/SparseCholesky>

namespace weft::sim {
namespace {

// A symmetric positive definite 3×3-block matrix with the coupling of a cloth grid: n×n
// vertices, a random SPD 3×3 block on each edge and diagonal of the grid (a spring's [H −H;
// −H H]) plus a mass on the diagonal. The full matrix.
SparseMatrix grid_system(int n, double mass, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> t;
  const auto add_block = [&](int p, int q, const Eigen::Matrix3d& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * p + r, 3 * q + c, b(r, c));
  };
  for (int v = 0; v < n * n; ++v) add_block(v, v, mass * Eigen::Matrix3d::Identity());
  const auto spring = [&](int a, int b) {
    Eigen::Matrix3d g;
    for (int k = 0; k < 9; ++k) g(k / 3, k % 3) = u(rng);
    const Eigen::Matrix3d H = g * g.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    add_block(a, a, H);
    add_block(b, b, H);
    add_block(a, b, -H);
    add_block(b, a, -H);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * n + j;
      if (j + 1 < n) spring(v, v + 1);
      if (i + 1 < n) spring(v, v + n);
      if (i + 1 < n && j + 1 < n) spring(v, v + n + 1);
    }
  SparseMatrix A(3 * n * n, 3 * n * n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

SparseMatrix lower(const SparseMatrix& full) {
  SparseMatrix l = full.triangularView<Eigen::Lower>();
  l.makeCompressed();
  return l;
}

// Conjugate gradients analysed and set up for the full symmetric matrix A.
std::unique_ptr<BlockConjugateGradient> prepared(const SparseMatrix& A, int threads = 1) {
  auto cg = std::make_unique<BlockConjugateGradient>(threads);
  cg->analyze(lower(A));
  cg->set_matrix(lower(A));
  return cg;
}

Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = g(rng);
  return b;
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
