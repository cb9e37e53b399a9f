// SparseSpdSolver (sim/linear): each back-end solves the systems weft builds — fast projection's
// J M⁻¹ Jᵀ and implicit Euler's M (1 + h α) + h² K on a perturbed cloth — to round-off, keeps
// its analysis across refactorizations with new values, says no to matrices that are not
// positive definite, and agrees with the other back-end. The cholmod back-end is tested in each
// ordering and factorization kind (sim/linear/cholmod_solver.h).

#include "sim/linear/sparse_spd_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/check.h"
#include "sim/linear/cholmod_solver.h"
#include "sim/linear/sparsity_pattern.h"
#include "tests/support/test_matrices.h"

namespace weft::sim {
namespace {

using test_matrices::ClothSample;
using test_matrices::make_cloth_sample;

bool built_with(SparseBackend backend) {
  for (SparseBackend available : available_sparse_backends()) {
    if (available == backend) return true;
  }
  return false;
}

// One way to make a solver of the back-end under test: the factory's default, and for cholmod
// each ordering × factorization kind.
struct SolverVariant {
  std::string name;
  std::function<std::unique_ptr<SparseSpdSolver>()> make;
  bool natural_ordering = false;  // O(n^1.5) fill on these grids: kept to the small matrices
};

std::vector<SolverVariant> solver_variants(SparseBackend backend) {
  std::vector<SolverVariant> variants;
  variants.push_back({std::string(sparse_backend_name(backend)) + " (default)",
                      [backend] { return make_sparse_spd_solver(backend); }});
  if (backend == SparseBackend::cholmod) {
    for (const CholmodSettings& settings : all_cholmod_settings()) {
      variants.push_back({"cholmod " + cholmod_settings_name(settings),
                          [settings] { return make_cholmod_solver(settings); },
                          settings.ordering == CholmodOrdering::natural});
    }
  }
  return variants;
}

// A right-hand side with every entry different and none zero.
Eigen::VectorXd test_rhs(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = 1.0 + 0.5 * std::sin(0.37 * static_cast<double>(i));
  return b;
}

double relative_residual(const SparseMatrix& A, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  return (A * x - b).norm() / b.norm();
}

// Solves A x = b after analysing and factorizing A; fails the test when factorize() refuses.
Eigen::VectorXd analyze_factorize_solve(SparseSpdSolver& solver, const SparseMatrix& A,
                                        const Eigen::VectorXd& b) {
  solver.analyze(A);
  EXPECT_TRUE(solver.factorize(A)) << solver.last_failure();
  return solver.solve(b);
}

class SparseSpdBackend : public ::testing::TestWithParam<SparseBackend> {
 protected:
  void SetUp() override {
    if (!built_with(GetParam())) {
      GTEST_SKIP() << "back-end \"" << sparse_backend_name(GetParam())
                   << "\" is not in this build (weft was built without CHOLMOD: install "
                      "libsuitesparse-dev and configure with -DWEFT_WITH_CHOLMOD=ON)";
    }
  }
};

TEST_P(SparseSpdBackend, SolvesProjectionMatrixToRoundOff) {
  for (const Index n : {16, 33}) {
    const ClothSample sample = make_cloth_sample(n, 7);
    const SparseMatrix A = test_matrices::projection_matrix(sample);
    const SparseMatrix lower = A.triangularView<Eigen::Lower>();
    const Eigen::VectorXd b = test_rhs(A.rows());
    for (const SolverVariant& variant : solver_variants(GetParam())) {
      if (variant.natural_ordering && n > 16) continue;
      SCOPED_TRACE(variant.name + ", " + std::to_string(n) + "² grid, " + std::to_string(A.rows()) +
                   " constraints");
      const auto solver = variant.make();
      EXPECT_EQ(solver->backend(), GetParam());
      const Eigen::VectorXd x = analyze_factorize_solve(*solver, A, b);
      EXPECT_LT(relative_residual(A, x, b), 1e-10);
      EXPECT_TRUE(solver->last_failure().empty()) << solver->last_failure();
      // Only the lower triangle is read: giving just that changes nothing.
      const Eigen::VectorXd x_lower = analyze_factorize_solve(*solver, lower, b);
      EXPECT_LT(relative_residual(A, x_lower, b), 1e-10);
    }
  }
}

TEST_P(SparseSpdBackend, SolvesImplicitEulerMatrixToRoundOff) {
  const ClothSample sample = make_cloth_sample(16, 3);
  const SparseMatrix A = test_matrices::implicit_euler_matrix(sample);
  const Eigen::VectorXd b = test_rhs(A.rows());
  for (const SolverVariant& variant : solver_variants(GetParam())) {
    SCOPED_TRACE(variant.name);
    const auto solver = variant.make();
    EXPECT_LT(relative_residual(A, analyze_factorize_solve(*solver, A, b), b), 1e-10);
  }
}

// Analyse once, then factorize matrices with the same pattern and other values: the cloth in
// other positions, and the first again.
TEST_P(SparseSpdBackend, RefactorizesNewValuesWithOneAnalysis) {
  const Index n = 33;
  std::vector<SparseMatrix> matrices;
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    matrices.push_back(test_matrices::projection_matrix(make_cloth_sample(n, seed)));
  }
  matrices.push_back(matrices.front());
  for (const SparseMatrix& A : matrices) {  // the same pattern
    ASSERT_TRUE(linear_detail::SparsityPattern(matrices.front()).matches(A));
  }
  ASSERT_GT((matrices[1] - matrices[0]).norm(), 1e-3 * matrices[0].norm());
  const Eigen::VectorXd b = test_rhs(matrices.front().rows());
  for (const SolverVariant& variant : solver_variants(GetParam())) {
    if (variant.natural_ordering) continue;
    SCOPED_TRACE(variant.name);
    const auto solver = variant.make();
    solver->analyze(matrices.front());
    for (std::size_t k = 0; k < matrices.size(); ++k) {
      SCOPED_TRACE("matrix " + std::to_string(k));
      ASSERT_TRUE(solver->factorize(matrices[k])) << solver->last_failure();
      EXPECT_LT(relative_residual(matrices[k], solver->solve(b), b), 1e-10);
    }
  }
}

// A copy of A with row and column k scaled by `factor` (diagonal by factor², pattern kept).
SparseMatrix scale_row_and_column(SparseMatrix A, int k, double factor) {
  for (int column = 0; column < A.outerSize(); ++column) {
    for (SparseMatrix::InnerIterator it(A, column); it; ++it) {
      if (it.row() == k) it.valueRef() *= factor;
      if (it.col() == k) it.valueRef() *= factor;
    }
  }
  return A;
}

TEST_P(SparseSpdBackend, SaysNoToMatricesThatAreNotPositiveDefinite) {
  const ClothSample sample = make_cloth_sample(16, 5);
  const SparseMatrix A = test_matrices::projection_matrix(sample);
  const int middle = static_cast<int>(A.rows() / 2);

  // A constraint between two pinned vertices: an empty row and column (no diagonal entry).
  ClothSample pinned_edge = sample;
  const ClothMesh& mesh = pinned_edge.mesh;
  const Index corner = mesh.index(0, mesh.nv - 1), next = mesh.index(1, mesh.nv - 1);  // u0v1
  ASSERT_EQ(pinned_edge.inv_mass[corner], 0.0);
  pinned_edge.inv_mass[next] = 0.0;
  std::vector<EdgeConstraint> constraints = test_matrices::warp_weft_constraints(pinned_edge);
  constraints.push_back(
      {corner, next, (mesh.material_coords[next] - mesh.material_coords[corner]).norm()});
  const SparseMatrix empty_row =
      test_matrices::projection_matrix(constraints, pinned_edge.x, pinned_edge.inv_mass);
  ASSERT_EQ(empty_row.col(empty_row.cols() - 1).nonZeros(), 0);

  SparseMatrix with_nan = A;
  with_nan.coeffRef(middle, middle) = std::nan("");
  SparseMatrix indefinite = A;  // e_kᵀ A e_k < 0
  indefinite.coeffRef(middle, middle) *= -1.0;

  const struct {
    const char* what;
    SparseMatrix matrix;
  } bad_cases[] = {
      {"a zero row and column, pattern kept", scale_row_and_column(A, middle, 0.0)},
      {"an empty row and column (a constraint between two pins)", empty_row},
      {"negative definite", -A},
      {"indefinite: one negative diagonal entry", indefinite},
      {"a NaN entry", with_nan},
  };
  const Eigen::VectorXd b = test_rhs(A.rows());
  for (const SolverVariant& variant : solver_variants(GetParam())) {
    SCOPED_TRACE(variant.name);
    const auto solver = variant.make();
    for (const auto& bad : bad_cases) {
      SCOPED_TRACE(bad.what);
      solver->analyze(bad.matrix);
      EXPECT_FALSE(solver->factorize(bad.matrix));
      EXPECT_FALSE(solver->last_failure().empty());
      EXPECT_THROW(solver->solve(test_rhs(bad.matrix.rows())), base::InternalError);
    }
    // The same pattern with good values factorizes again after a failure.
    solver->analyze(A);
    ASSERT_FALSE(solver->factorize(-A));
    ASSERT_TRUE(solver->factorize(A)) << solver->last_failure();
    EXPECT_TRUE(solver->last_failure().empty());
    EXPECT_LT(relative_residual(A, solver->solve(b), b), 1e-10);
  }
}

TEST_P(SparseSpdBackend, MisuseIsAProgrammingError) {
  const SparseMatrix A = test_matrices::projection_matrix(make_cloth_sample(8, 1));
  const SparseMatrix other = test_matrices::projection_matrix(make_cloth_sample(9, 1));
  const auto solver = make_sparse_spd_solver(GetParam());
  EXPECT_THROW((void)solver->factorize(A), base::InternalError);  // before analyze
  solver->analyze(A);
  EXPECT_THROW(solver->solve(test_rhs(A.rows())), base::InternalError);  // before factorize
  EXPECT_THROW((void)solver->factorize(other), base::InternalError);     // another pattern
  ASSERT_TRUE(solver->factorize(A));
  EXPECT_THROW(solver->solve(test_rhs(A.rows() + 1)), base::InternalError);
  EXPECT_THROW(solver->analyze(SparseMatrix(3, 4)), base::InternalError);
}

INSTANTIATE_TEST_SUITE_P(, SparseSpdBackend,
                         ::testing::Values(SparseBackend::eigen_ldlt, SparseBackend::cholmod),
                         [](const ::testing::TestParamInfo<SparseBackend>& param_info) {
                           return std::string(sparse_backend_name(param_info.param));
                         });

TEST(SparseSpdSolver, BackendNamesRoundTrip) {
  for (const SparseBackend backend : {SparseBackend::eigen_ldlt, SparseBackend::cholmod}) {
    EXPECT_EQ(sparse_backend_from_name(sparse_backend_name(backend)), backend);
  }
  try {
    (void)sparse_backend_from_name("umfpack");
    FAIL() << "an unknown name was accepted";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'umfpack'"), std::string::npos) << message;
    EXPECT_NE(message.find("eigen_ldlt"), std::string::npos) << message;
    EXPECT_NE(message.find("cholmod"), std::string::npos) << message;
  }
}

TEST(SparseSpdSolver, DefaultIsAvailableAndEachAvailableBackendIsMade) {
  EXPECT_TRUE(built_with(default_sparse_backend()));
  EXPECT_TRUE(built_with(SparseBackend::eigen_ldlt));
  for (const SparseBackend backend : available_sparse_backends()) {
    EXPECT_EQ(make_sparse_spd_solver(backend)->backend(), backend);
  }
  if (!built_with(SparseBackend::cholmod)) {
    try {
      (void)make_sparse_spd_solver(SparseBackend::cholmod);
      FAIL() << "make_sparse_spd_solver(cholmod) succeeded in a build without CHOLMOD";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("without CHOLMOD"), std::string::npos)
          << error.what();
    }
  }
}

TEST(SparseSpdSolver, CholmodAndEigenAgree) {
  if (!built_with(SparseBackend::cholmod)) {
    GTEST_SKIP() << "weft was built without CHOLMOD: nothing to compare eigen_ldlt with";
  }
  const ClothSample sample = make_cloth_sample(33, 11);
  const struct {
    const char* what;
    SparseMatrix matrix;
  } cases[] = {{"projection, 33² grid", test_matrices::projection_matrix(sample)},
               {"implicit Euler, 33² grid", test_matrices::implicit_euler_matrix(sample)}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const Eigen::VectorXd b = test_rhs(c.matrix.rows());
    const auto eigen = make_sparse_spd_solver(SparseBackend::eigen_ldlt);
    const Eigen::VectorXd reference = analyze_factorize_solve(*eigen, c.matrix, b);
    for (const SolverVariant& variant : solver_variants(SparseBackend::cholmod)) {
      if (variant.natural_ordering) continue;
      SCOPED_TRACE(variant.name);
      const auto solver = variant.make();
      const Eigen::VectorXd x = analyze_factorize_solve(*solver, c.matrix, b);
      EXPECT_LT((x - reference).norm(), 1e-9 * reference.norm());
    }
  }
}

}  // namespace
}  // namespace weft::sim
