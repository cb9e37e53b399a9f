// The line preconditioner (sim/linear/grid_line_preconditioner.h): exact for a sheet held by
// its shear springs, symmetric positive definite on a generic grid matrix, fewer conjugate
// gradient iterations than block Jacobi on a stiff cloth, block Jacobi where a line cannot be
// factored, and the same steps as block Jacobi through the simulator.
#include "sim/linear/grid_line_preconditioner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "sim/energies/spring_hessian.h"
#include "sim/grid.h"
#include "sim/integrators/time_integrator.h"
#include "sim/linear/block_conjugate_gradient.h"
#include "sim/mass_spring.h"
#include "sim/material/material.h"
#include "sim/pins.h"
#include "sim/simulator.h"
#include "tests/sim/cg_hang.h"
#include "tests/support/block_grid_matrix.h"
#include "tests/support/test_matrices.h"

namespace weft::sim {
namespace {

using Grid = BlockConjugateGradient::GridPreconditioner;
using test_matrices::lower_triangle;
using test_matrices::random_vector;

// Conjugate gradients on the full matrix A of an nu × nv grid, with the lines (`grid`) or block
// Jacobi.
std::unique_ptr<BlockConjugateGradient> prepared(const SparseMatrix& A, Index nu, Index nv,
                                                 bool lines, int threads = 1,
                                                 Grid grid = Grid::lines) {
  auto cg = std::make_unique<BlockConjugateGradient>(threads);
  cg->analyze(lower_triangle(A), lines ? nu : 0, lines ? nv : 0, grid);
  cg->set_matrix(lower_triangle(A));
  return cg;
}

// A flat n×n sheet in the xy plane, unit spacing, mass m on each vertex and a spring of
// stiffness k along both diagonals of every cell, at rest (each block k d dᵀ).
SparseMatrix shear_sheet(int n, double m, double k) {
  std::vector<Eigen::Triplet<double>> t;
  const auto add = [&](int p, int q, const Eigen::Matrix3d& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * p + r, 3 * q + c, b(r, c));
  };
  const auto spring = [&](int a, int b, const Eigen::Vector3d& d) {
    const Eigen::Matrix3d H = k * d.normalized() * d.normalized().transpose();
    add(a, a, H), add(b, b, H), add(a, b, -H), add(b, a, -H);
  };
  for (int v = 0; v < n * n; ++v) add(v, v, m * Eigen::Matrix3d::Identity());
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      spring(j * n + i, (j + 1) * n + i + 1, Eigen::Vector3d(1, 1, 0));
      spring(j * n + i + 1, (j + 1) * n + i, Eigen::Vector3d(-1, 1, 0));
    }
  SparseMatrix A(3 * n * n, 3 * n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Each shear diagonal couples one component (along it) along its own line: the preconditioner
// is A⁻¹, so conjugate gradients finish in one iteration however stiff the springs are, where
// block Jacobi needs many.
TEST(GridLinePreconditioner, IsTheInverseOfASheetHeldByItsShearSprings) {
  const int n = 16;
  const SparseMatrix A = shear_sheet(n, 1e-4, 1.0);
  const Eigen::VectorXd b = random_vector(A.rows(), 1);
  Eigen::VectorXd x, y;
  const auto lines = prepared(A, n, n, true)->solve(b, x, 1e-10, 500);
  const auto jacobi = prepared(A, n, n, false)->solve(b, y, 1e-10, 500);
  std::printf("shear sheet 16²: lines %d, block Jacobi %d iterations\n", lines.iterations,
              jacobi.iterations);
  EXPECT_EQ(lines.iterations, 1);
  EXPECT_LE(lines.relative_residual, 1e-10);
  EXPECT_GT(jacobi.iterations, 20);
}

// Implicit Euler holds resting contacts by a penalty κ n nᵀ on a vertex's diagonal block, κ a
// million times the block's scale. Along a normal tilted from the sheet's, that penalty
// couples the vertex's components in its frame; the frame takes the penalty's axis, so the
// line solves keep it and conjugate gradients still take a tenth of block Jacobi's iterations
// (without it, more than block Jacobi's).
TEST(GridLinePreconditioner, KeepsTheAxisOfAContactPenalty) {
  const int n = 16;
  SparseMatrix A = shear_sheet(n, 1e-4, 1.0);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.04, -0.03, 1.0).normalized();  // 3° off
  const Eigen::Matrix3d penalty = 1e6 * 1e-4 * normal * normal.transpose();
  for (int v = 0; v < n * n; v += 7)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) A.coeffRef(3 * v + r, 3 * v + c) += penalty(r, c);
  A.makeCompressed();
  const Eigen::VectorXd b = random_vector(A.rows(), 8);
  Eigen::VectorXd x, y;
  const auto lines = prepared(A, n, n, true)->solve(b, x, 1e-8, 500);
  const auto jacobi = prepared(A, n, n, false)->solve(b, y, 1e-8, 500);
  std::printf("shear sheet 16² with contacts: lines %d, block Jacobi %d iterations\n",
              lines.iterations, jacobi.iterations);
  EXPECT_LT(10 * lines.iterations, jacobi.iterations);
  EXPECT_LE(lines.relative_residual, 1e-8);
}

// The preconditioner of A on its n×n grid, as a dense matrix (B r for every unit vector r).
Eigen::MatrixXd dense_preconditioner(const SparseMatrix& A, Index n) {
  BlockConjugateGradient cg(1);
  cg.analyze(lower_triangle(A));
  cg.set_matrix(lower_triangle(A));
  GridLinePreconditioner lines(cg.matrix(), n, n);
  EXPECT_TRUE(lines.update(cg.matrix()));
  const Eigen::Index rows = A.rows();
  Eigen::MatrixXd B(rows, rows);
  Eigen::VectorXd z(rows);
  for (Eigen::Index c = 0; c < rows; ++c) {
    lines.apply(Eigen::VectorXd::Unit(rows, c), z);
    B.col(c) = z;
  }
  return B;
}

// On a generic grid matrix (random SPD blocks on every edge, both diagonals and two-step
// couplings) the preconditioner, as a dense matrix, is symmetric and positive definite.
TEST(GridLinePreconditioner, IsSymmetricPositiveDefinite) {
  const int n = 7;
  const Eigen::MatrixXd B =
      dense_preconditioner(test_matrices::grid_system(n, 0.05, 21, 1.0, true, true), n);
  EXPECT_LT((B - B.transpose()).cwiseAbs().maxCoeff(), 1e-12 * B.cwiseAbs().maxCoeff());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (B + B.transpose()));
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

// Implicit Euler's matrix for an inextensible cloth as the simulator builds it: M + h² K with
// the shear springs' Hessians (stiffness k_shear) on the diagonals of each cell and the carried
// tension's k_tension I on the warp and weft edges, at the sample's positions.
SparseMatrix inextensible_matrix(const test_matrices::ClothSample& sample, double h_s,
                                 double k_shear, double k_tension) {
  const MassSpringModel model(sample.mesh, Material{});
  std::vector<Eigen::Triplet<double>> t;
  const auto add = [&](Index p, Index q, const Eigen::Matrix3d& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * p + r, 3 * q + c, b(r, c));
  };
  for (Index v = 0; v < sample.mesh.vertex_count(); ++v)
    add(v, v, sample.mass_kg[v] * Eigen::Matrix3d::Identity());
  for (const Spring& s : model.springs()) {
    const Mat3 H = h_s * h_s *
                   (s.kind == SpringKind::shear
                        ? spring_hessian_b_projected(sample.x.row(s.a), sample.x.row(s.b), s.rest_m, k_shear)
                        : Mat3(k_tension * Mat3::Identity()));
    add(s.a, s.a, H), add(s.b, s.b, H), add(s.a, s.b, -H), add(s.b, s.a, -H);
  }
  const Index rows = 3 * sample.mesh.vertex_count();
  SparseMatrix A(rows, rows);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Mirrored across the grid's middle column (vertex (i, j) to (n − 1 − i, j), x to −x), a
// matrix's preconditioner is the mirrored preconditioner: the ↗ and ↘ lines and frame axes
// trade places, and a symmetric scene is not pushed to one side by its solves. Checked on a
// generic grid matrix and on a cloth's, whose shear springs set the frames (there the frames
// must treat the ↗ and ↘ axes alike: with the ↘ axis merely made orthogonal to the ↗ one, the
// mirrored preconditioner differs by 4 % of its largest entry).
void expect_mirror_image(const SparseMatrix& A, int n) {
  std::vector<Eigen::Triplet<double>> q;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        q.emplace_back(3 * (j * n + n - 1 - i) + c, 3 * (j * n + i) + c, c == 0 ? -1.0 : 1.0);
  SparseMatrix Q(A.rows(), A.cols());
  Q.setFromTriplets(q.begin(), q.end());
  const SparseMatrix mirrored = Q * A * SparseMatrix(Q.transpose());
  const Eigen::MatrixXd B = dense_preconditioner(A, n);
  const Eigen::MatrixXd expected = Eigen::MatrixXd(Q) * B * Eigen::MatrixXd(Q).transpose();
  const Eigen::MatrixXd B_mirrored = dense_preconditioner(mirrored, n);
  EXPECT_LT((B_mirrored - expected).cwiseAbs().maxCoeff(), 1e-10 * B.cwiseAbs().maxCoeff());
}

TEST(GridLinePreconditioner, IsTheMirrorImageOfItsMirroredMatrix) {
  expect_mirror_image(test_matrices::grid_system(7, 0.05, 31, 1.0, true, true), 7);
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(7, 5, 0.2);
  expect_mirror_image(inextensible_matrix(sample, 1.0 / 120.0, 41.0, 4.1), 7);
}

// A perturbed 48² hanging cloth held inextensible, wool's shear rigidity on its diagonals
// (h²k/m = 33) and a tension of a tenth of it along its edges: fewer than half block Jacobi's
// iterations, to the same solution.
TEST(GridLinePreconditioner, NeedsFewerIterationsThanBlockJacobiOnAStiffCloth) {
  const Index n = 48;
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(n, 3, 0.05);
  const SparseMatrix A = inextensible_matrix(sample, 1.0 / 120.0, 41.0, 4.1);
  const Eigen::VectorXd b = random_vector(A.rows(), 4);
  Eigen::VectorXd x, y;
  const auto cg_lines = prepared(A, n, n, true);
  ASSERT_TRUE(cg_lines->lines_in_use());
  const auto lines = cg_lines->solve(b, x, 1e-8, 2000);
  const auto jacobi = prepared(A, n, n, false)->solve(b, y, 1e-8, 2000);
  std::printf("cloth 48²: lines %d, block Jacobi %d iterations\n", lines.iterations,
              jacobi.iterations);
  EXPECT_LT(2 * lines.iterations, jacobi.iterations);
  const Eigen::SimplicialLDLT<SparseMatrix> direct(A);
  const Eigen::VectorXd exact = direct.solve(b);
  EXPECT_LT((x - exact).norm() / exact.norm(), 1e-6);
  EXPECT_LT((y - exact).norm() / exact.norm(), 1e-6);
}

// lines_when_slow: on the stiff cloth above (block Jacobi: over 100 iterations) the probe's
// rate sends the solve on to the lines, and it ends in fewer than half block Jacobi's
// iterations; with a step 15 times shorter (h²k/m 225 times smaller) block Jacobi converges
// in 9 iterations, past the probe's 6: the lines are not set up, and the solve is block
// Jacobi's, to the bit.
TEST(GridLinePreconditioner, WhenSlowTakesTheLinesOnlyWhereBlockJacobiWouldBeSlow) {
  const Index n = 48;
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(n, 3, 0.05);
  const Eigen::VectorXd b = random_vector(3 * n * n, 4);
  for (const double h_s : {1.0 / 120.0, 1.0 / 1800.0}) {
    const SparseMatrix A = inextensible_matrix(sample, h_s, 41.0, 4.1);
    Eigen::VectorXd x, y;
    const auto cg = prepared(A, n, n, true, 1, Grid::lines_when_slow);
    const auto when_slow = cg->solve(b, x, 1e-8, 2000);
    const auto jacobi = prepared(A, n, n, false)->solve(b, y, 1e-8, 2000);
    std::printf("cloth 48², h = %.5f s: lines when slow %d, block Jacobi %d iterations\n", h_s,
                when_slow.iterations, jacobi.iterations);
    EXPECT_LE(when_slow.relative_residual, 1e-8);
    if (h_s > 1e-3) {
      EXPECT_TRUE(cg->lines_in_use());
      EXPECT_LT(2 * when_slow.iterations, jacobi.iterations);
    } else {
      EXPECT_FALSE(cg->lines_in_use());
      EXPECT_LE(jacobi.iterations, BlockConjugateGradient::kSlowIterations);
      EXPECT_EQ(when_slow.iterations, jacobi.iterations);
      EXPECT_TRUE(x == y);
    }
  }
}

// A 3 × 1 grid whose matrix [1 a c; a 1 a; c a 1] ⊗ I is positive definite (a = 0.75,
// c = 0.5) but whose line, [1 a 0; a 1 a; 0 a 1], is not (1 − √2 a < 0): the factorization
// fails, block Jacobi preconditions instead, and the solve still converges.
TEST(GridLinePreconditioner, ALineThatCannotBeFactoredLeavesBlockJacobi) {
  const double a = 0.75, c = 0.5;
  Eigen::Matrix3d scalar;
  scalar << 1, a, c, a, 1, a, c, a, 1;
  std::vector<Eigen::Triplet<double>> t;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q)
      for (int d = 0; d < 3; ++d) t.emplace_back(3 * p + d, 3 * q + d, scalar(p, q));
  SparseMatrix A(9, 9);
  A.setFromTriplets(t.begin(), t.end());
  const auto cg = prepared(A, 3, 1, true);
  EXPECT_FALSE(cg->lines_in_use());
  const Eigen::VectorXd b = random_vector(9, 5);
  Eigen::VectorXd x;
  const auto r = cg->solve(b, x, 1e-10, 100);
  EXPECT_FALSE(r.breakdown);
  EXPECT_LE(r.relative_residual, 1e-10);
}

// The product is shared among threads, the line solves are not: the same bits for 1 and 2.
TEST(GridLinePreconditioner, GivesTheSameBitsForAnyThreadCount) {
  const Index n = 40;
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(n, 6);
  const SparseMatrix A = test_matrices::implicit_euler_matrix(sample, 1.0 / 120.0, 1.0, 50.0);
  const Eigen::VectorXd b = random_vector(A.rows(), 7);
  Eigen::VectorXd x1, x2;
  const auto r1 = prepared(A, n, n, true, 1)->solve(b, x1, 1e-6, 500);
  const auto r2 = prepared(A, n, n, true, 2)->solve(b, x2, 1e-6, 500);
  EXPECT_EQ(r1.iterations, r2.iterations);
  EXPECT_TRUE(x1 == x2);
}

// Through the simulator: a 33² mass-spring hang stepped by implicit Euler with CG to 1e-9 moves
// the same with block Jacobi and the lines (the solution does not depend on the path to it),
// and the lines need far fewer iterations.
TEST(GridLinePreconditioner, TheSimulatorTakesTheSameStepsAsWithBlockJacobi) {
  test_cloth::expect_same_steps_in_fewer_iterations(CgPreconditioner::lines, "lines");
}

// "auto" gives an inextensible cloth on a grid the lines for its slow solves, a mass-spring
// cloth block Jacobi (where the lines were measured slower), and the simulator says which it
// took.
TEST(GridLinePreconditioner, AutoTakesTheLinesForAnInextensibleCloth) {
  GridSpec grid;
  grid.nu = grid.nv = 12;
  const ClothMesh mesh = make_grid(grid);
  const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  for (const bool inextensible : {true, false}) {
    SimSettings s;
    s.integrator = Integrator::implicit_euler;
    s.implicit_solve = ImplicitSolve::conjugate_gradient;
    if (inextensible) s.projection.method = ProjectionMethod::fast_projection;
    const Simulator sim(mesh, Material{}, pins, s);
    const std::string expected =
        inextensible ? "(auto: block_jacobi, lines when slow)" : "(auto: block_jacobi)";
    bool found = false;
    for (const std::string& line : sim.explain()) found = found || line.find(expected) != std::string::npos;
    EXPECT_TRUE(found) << expected;
  }
}

}  // namespace
}  // namespace weft::sim
