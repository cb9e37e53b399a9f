// SparseSpdSolver back-ends and CHOLMOD variants on the matrices weft solves
// (tests/support/test_matrices.h), on n×n cloth grids:
//   factorize_solve/<matrix>/<variant>/<n>  one numeric factorization and one solve, the
//                                           pattern analysed once beforehand (what every
//                                           fast-projection iteration and implicit step pays);
//   analyze/<matrix>/<variant>/<n>          the symbolic analysis alone (paid once per pattern).
// <matrix> is projection (J M⁻¹ Jᵀ, #C = 2n(n−1) rows) or implicit_euler (M(1+hα) + h²K, 3n²
// rows). Every variant runs on one thread here (Debian's reference BLAS), so the CPU column is
// the one to read when other work shares the machine; with a threaded BLAS read Time instead.
//
// Run: build/bench/sparse_solver_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only
// The figures behind default_sparse_backend() are in sim/linear/sparse_spd_solver.cpp.

#include <benchmark/benchmark.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "sim/linear/cholmod_solver.h"
#include "sim/linear/sparse_spd_solver.h"
#include "tests/support/test_matrices.h"

namespace {

using namespace weft::sim;

enum class MatrixKind { projection, implicit_euler };

const char* matrix_kind_name(MatrixKind kind) {
  return kind == MatrixKind::projection ? "projection" : "implicit_euler";
}

SparseMatrix make_matrix(MatrixKind kind, Index n) {
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(n, 1);
  return kind == MatrixKind::projection ? test_matrices::projection_matrix(sample)
                                        : test_matrices::implicit_euler_matrix(sample);
}

Eigen::VectorXd make_rhs(Eigen::Index rows) {
  Eigen::VectorXd b(rows);
  for (Eigen::Index i = 0; i < rows; ++i) b[i] = std::cos(0.1 * static_cast<double>(i));
  return b;
}

struct Variant {
  std::string name;  // "eigen_ldlt/amd", "cholmod/supernodal/metis", …
  std::function<std::unique_ptr<SparseSpdSolver>()> make;
  bool natural_ordering = false;
};

std::vector<Variant> variants() {
  std::vector<Variant> all{
      {"eigen_ldlt/amd", [] { return make_sparse_spd_solver(SparseBackend::eigen_ldlt); }}};
  for (SparseBackend backend : available_sparse_backends()) {
    if (backend != SparseBackend::cholmod) continue;
    for (const CholmodSettings& settings : all_cholmod_settings()) {
      all.push_back({"cholmod/" + cholmod_settings_name(settings),
                     [settings] { return make_cholmod_solver(settings); },
                     settings.ordering == CholmodOrdering::natural});
    }
  }
  return all;
}

void factorize_solve(benchmark::State& state, const Variant& variant, MatrixKind kind, Index n) {
  const SparseMatrix A = make_matrix(kind, n);
  const Eigen::VectorXd b = make_rhs(A.rows());
  const auto solver = variant.make();
  solver->analyze(A);
  Eigen::VectorXd x;
  for (auto _ : state) {
    if (!solver->factorize(A)) {
      state.SkipWithError(("factorize failed: " + solver->last_failure()).c_str());
      break;
    }
    x = solver->solve(b);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["rows"] = static_cast<double>(A.rows());
  state.counters["residual"] = x.size() ? (A * x - b).norm() / b.norm() : 0.0;
}

void analyze(benchmark::State& state, const Variant& variant, MatrixKind kind, Index n) {
  const SparseMatrix A = make_matrix(kind, n);
  const auto solver = variant.make();
  for (auto _ : state) solver->analyze(A);
  state.counters["rows"] = static_cast<double>(A.rows());
}

// The natural ordering fills in badly (J M⁻¹ Jᵀ's rows are all warp edges, then all weft
// edges: a profile of ~n²/2; the implicit matrix's is ~3n): kept to the sizes where it fits.
bool affordable(const Variant& variant, MatrixKind kind, Index n) {
  if (!variant.natural_ordering) return true;
  return kind == MatrixKind::projection ? n <= 32 : n <= 64;
}

bool register_all() {
  for (const MatrixKind kind : {MatrixKind::projection, MatrixKind::implicit_euler}) {
    for (const Variant& variant : variants()) {
      for (const Index n : {32, 64, 128}) {
        if (!affordable(variant, kind, n)) continue;
        const std::string suffix =
            std::string(matrix_kind_name(kind)) + "/" + variant.name + "/" + std::to_string(n);
        benchmark::RegisterBenchmark(("factorize_solve/" + suffix).c_str(), factorize_solve,
                                     variant, kind, n)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("analyze/" + suffix).c_str(), analyze, variant, kind, n)
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  return true;
}

const bool g_registered = register_all();

}  // namespace
