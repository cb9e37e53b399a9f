// The grid multigrid (sim/linear/grid_multigrid.h): its coarse matrices are PᵀAP for the
// bilinear P its header describes, its cycle is a symmetric positive definite operator, and as
// conjugate gradients' preconditioner it converges in a number of iterations that does not grow
// with the grid, gives the same bits for any thread count, and copes with decoupled vertices.
#include "sim/linear/grid_multigrid.h"

#include <gtest/gtest.h>

#include <cstdio>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "sim/grid.h"
#include "sim/integrators/time_integrator.h"
#include "sim/linear/block_conjugate_gradient.h"
#include "tests/sim/cg_hang.h"
#include "tests/support/block_grid_matrix.h"

namespace weft::sim {
namespace {

using test_matrices::grid_system;
using test_matrices::lower_triangle;
using test_matrices::random_vector;

// A's pattern and values in `cg`, and the multigrid of its n×n grid, updated.
GridMultigrid updated_multigrid(const SparseMatrix& A, int n, BlockConjugateGradient& cg) {
  cg.analyze(lower_triangle(A));
  cg.set_matrix(lower_triangle(A));
  std::optional<GridMultigrid> mg = GridMultigrid::make(cg.matrix(), n, n);
  EXPECT_TRUE(mg);
  mg->update(cg.matrix());
  return std::move(*mg);
}

// Bilinear prolongation from the (nu/2 + 1) × (nv/2 + 1) grid to the nu × nv grid, written from
// the rule in grid_multigrid.h (not from its code): fine (i, j) interpolates its coarse
// neighbours (i/2 or its two neighbours when i is odd, likewise j), 3 DOFs each.
Eigen::MatrixXd bilinear_prolongation(Index nu, Index nv) {
  const Index cu = nu / 2 + 1, cv = nv / 2 + 1;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * nu * nv, 3 * cu * cv);
  for (Index j = 0; j < nv; ++j)
    for (Index i = 0; i < nu; ++i) {
      const std::vector<std::pair<Index, double>> ui =
          i % 2 == 0 ? std::vector<std::pair<Index, double>>{{i / 2, 1.0}}
                     : std::vector<std::pair<Index, double>>{{i / 2, 0.5}, {i / 2 + 1, 0.5}};
      const std::vector<std::pair<Index, double>> vj =
          j % 2 == 0 ? std::vector<std::pair<Index, double>>{{j / 2, 1.0}}
                     : std::vector<std::pair<Index, double>>{{j / 2, 0.5}, {j / 2 + 1, 0.5}};
      for (const auto& [ci, wi] : ui)
        for (const auto& [cj, wj] : vj)
          for (int c = 0; c < 3; ++c) P(3 * (j * nu + i) + c, 3 * (cj * cu + ci) + c) = wi * wj;
    }
  return P;
}

// A BlockConjugateGradient on the full matrix A, its grid n×n (multigrid) or none.
std::unique_ptr<BlockConjugateGradient> prepared(const SparseMatrix& A, int n, bool multigrid,
                                                 int threads = 1) {
  auto cg = std::make_unique<BlockConjugateGradient>(threads);
  cg->analyze(lower_triangle(A), multigrid ? n : 0, multigrid ? n : 0);
  cg->set_matrix(lower_triangle(A));
  return cg;
}

TEST(GridMultigrid, CoarseMatricesAreTheGalerkinProducts) {
  // 9 × 9 with couplings two steps apart: coarse 5 × 5, then 3 × 3.
  const int n = 9;
  const SparseMatrix A = grid_system(n, 0.05, 11, 1.0, true);
  BlockConjugateGradient cg(1);
  const GridMultigrid mg = updated_multigrid(A, n, cg);
  ASSERT_EQ(mg.levels(), 3);
  Eigen::MatrixXd fine = Eigen::MatrixXd(A);
  Index nu = n;
  for (int l = 1; l < mg.levels(); ++l) {
    const Eigen::MatrixXd P = bilinear_prolongation(nu, nu);
    const Eigen::MatrixXd expected = P.transpose() * fine * P;
    const Eigen::MatrixXd coarse = mg.coarse_matrix(l).to_dense();
    ASSERT_EQ(coarse.rows(), expected.rows());
    EXPECT_LT((coarse - expected).norm(), 1e-12 * expected.norm()) << "level " << l;
    fine = expected;
    nu = mg.coarse_nu(l);
  }
}

TEST(GridMultigrid, TheCycleIsSymmetricAndPositive) {
  const int n = 20;
  const SparseMatrix A = grid_system(n, 0.02, 12, 1.0, true);
  BlockConjugateGradient cg(1);
  const GridMultigrid mg = updated_multigrid(A, n, cg);
  std::vector<Eigen::Matrix3d> inverse;
  cg.matrix().invert_diagonal(inverse);
  for (unsigned seed = 0; seed < 4; ++seed) {
    const Eigen::VectorXd u = random_vector(A.rows(), 100 + seed), v = random_vector(A.rows(), 200 + seed);
    Eigen::VectorXd Bu, Bv;
    mg.apply(cg.matrix(), inverse, u, Bu, nullptr);
    mg.apply(cg.matrix(), inverse, v, Bv, nullptr);
    EXPECT_NEAR(u.dot(Bv), v.dot(Bu), 1e-12 * Bu.norm() * v.norm());
    EXPECT_GT(v.dot(Bv), 0.0);
  }
}

// Block Jacobi needs more iterations the finer the grid; the multigrid about the same number.
TEST(GridMultigrid, IterationsDoNotGrowWithTheGrid) {
  int jacobi[2], multigrid[2];
  const int sizes[2] = {16, 64};
  for (int s = 0; s < 2; ++s) {
    const int n = sizes[s];
    // Stiffness growing as n² against a mass falling as 1/n²: a taut cloth's h²k/m ∝ n³ or so.
    const SparseMatrix A = grid_system(n, 1.0 / (n * n), 13, 0.02 * n * n / 256.0, true);
    const Eigen::VectorXd b = random_vector(A.rows(), 14);
    Eigen::VectorXd x;
    jacobi[s] = prepared(A, n, false)->solve(b, x, 1e-6, 5000).iterations;
    x.resize(0);
    const auto r = prepared(A, n, true)->solve(b, x, 1e-6, 5000);
    EXPECT_LE(r.relative_residual, 1e-6);
    EXPECT_LE((b - A * x).norm() / b.norm(), 1e-6 * 1.0001);
    multigrid[s] = r.iterations;
  }
  std::printf("block Jacobi %d → %d, multigrid %d → %d iterations\n", jacobi[0], jacobi[1], multigrid[0], multigrid[1]);
  EXPECT_GT(jacobi[1], 2 * jacobi[0]) << jacobi[0] << " → " << jacobi[1];
  EXPECT_LE(multigrid[1], multigrid[0] + 4) << multigrid[0] << " → " << multigrid[1];
  EXPECT_LT(multigrid[1] * 4, jacobi[1]);
}

TEST(GridMultigrid, AgreesWithADirectSolveAndGivesTheSameBitsForAnyThreadCount) {
  const int n = 40;  // 1600 block rows: the product is shared by two threads
  const SparseMatrix A = grid_system(n, 0.01, 15, 1.0, true);
  const Eigen::VectorXd b = random_vector(A.rows(), 16);
  Eigen::VectorXd x[2];
  for (int threads = 1; threads <= 2; ++threads) {
    const auto cg = prepared(A, n, true, threads);
    ASSERT_GT(cg->multigrid_levels(), 2);
    const auto r = cg->solve(b, x[threads - 1], 1e-10, 500);
    EXPECT_FALSE(r.breakdown);
    EXPECT_LE(r.relative_residual, 1e-10);
  }
  EXPECT_TRUE((x[0].array() == x[1].array()).all());
  const Eigen::SimplicialLDLT<SparseMatrix> direct(A);
  EXPECT_LT((x[0] - direct.solve(b)).norm() / x[0].norm(), 1e-7);
}

// Pinned and unused vertices have identity rows and no coupling; a coarse vertex that only such
// vertices reach must not make its level singular.
TEST(GridMultigrid, DecoupledVerticesKeepTheCycleUsable) {
  const int n = 24;
  SparseMatrix A = grid_system(n, 0.01, 17);
  // Decouple the vertices of the first two rows (j = 0, 1), as unused vertices are.
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      const bool row_out = it.row() / 3 < 2 * n, col_out = it.col() / 3 < 2 * n;
      if (row_out || col_out) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
    }
  const Eigen::VectorXd b = random_vector(A.rows(), 18);
  Eigen::VectorXd x;
  const auto r = prepared(A, n, true)->solve(b, x, 1e-10, 500);
  EXPECT_FALSE(r.breakdown);
  EXPECT_LE((b - A * x).norm() / b.norm(), 1e-9);
  EXPECT_LT(r.iterations, 60);
}

TEST(GridMultigrid, NoHierarchyForSmallGridsOrFarCouplings) {
  BlockConjugateGradient cg(1);
  const SparseMatrix small = grid_system(4, 0.05, 19);  // 16 vertices: no coarser level needed
  cg.analyze(lower_triangle(small));
  EXPECT_FALSE(GridMultigrid::make(cg.matrix(), 4, 4));
  // A coupling across the grid (vertex 0 with the far corner): not a grid operator.
  SparseMatrix far = grid_system(12, 0.05, 20);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < far.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(far, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  const int last = 3 * (12 * 12 - 1);
  t.emplace_back(last, 0, 1e-3);
  t.emplace_back(0, last, 1e-3);
  far.setFromTriplets(t.begin(), t.end());
  far.makeCompressed();
  cg.analyze(lower_triangle(far));
  EXPECT_FALSE(GridMultigrid::make(cg.matrix(), 12, 12));
  cg.analyze(lower_triangle(grid_system(12, 0.05, 20)));  // the same grid without it
  EXPECT_TRUE(GridMultigrid::make(cg.matrix(), 12, 12));
}

// "auto" takes the multigrid from 150 × 150 vertices (where it was measured to pay), the lines
// below when the cloth's edges are held by a projection (for the solves block Jacobi would
// make slow), block Jacobi otherwise and on a triangle mesh (no grid); an explicit choice holds
// at any size.
TEST(GridMultigrid, AutomaticChoiceFollowsTheGridSize) {
  ImplicitSolveSettings s;
  ASSERT_EQ(s.preconditioner, CgPreconditioner::automatic);
  s.grid_nu = s.grid_nv = 149;
  EXPECT_FALSE(uses_multigrid(s));
  EXPECT_FALSE(uses_lines(s));  // a mass-spring cloth
  s.edges_constrained = true;
  EXPECT_TRUE(uses_lines(s));
  EXPECT_TRUE(lines_when_slow(s));  // "auto" takes them for the slow solves only
  s.grid_nu = s.grid_nv = 150;
  EXPECT_TRUE(uses_multigrid(s));
  EXPECT_FALSE(uses_lines(s));
  s.grid_nu = 300;
  s.grid_nv = 75;
  EXPECT_TRUE(uses_multigrid(s));
  s.grid_nu = s.grid_nv = 0;
  EXPECT_FALSE(uses_multigrid(s));
  EXPECT_FALSE(uses_lines(s));
  s.preconditioner = CgPreconditioner::lines;
  EXPECT_FALSE(uses_lines(s));
  s.grid_nu = s.grid_nv = 256;
  EXPECT_TRUE(uses_lines(s));
  EXPECT_FALSE(lines_when_slow(s));
  EXPECT_FALSE(uses_multigrid(s));
  s.preconditioner = CgPreconditioner::block_jacobi;
  EXPECT_FALSE(uses_multigrid(s));
  EXPECT_FALSE(uses_lines(s));
  s.preconditioner = CgPreconditioner::multigrid;
  s.grid_nu = s.grid_nv = 16;
  EXPECT_TRUE(uses_multigrid(s));
  EXPECT_FALSE(uses_lines(s));
}

// Through the simulator: a 33² mass-spring hang stepped by implicit Euler with CG to 1e-9 moves
// the same with either preconditioner (the solution does not depend on the path to it), and
// the multigrid, chosen by name below the automatic threshold, is the one that ran (far fewer
// iterations).
TEST(GridMultigrid, TheSimulatorTakesTheSameStepsWithEitherPreconditioner) {
  test_cloth::expect_same_steps_in_fewer_iterations(CgPreconditioner::multigrid, "multigrid");
}

}  // namespace
}  // namespace weft::sim
