// Implicit Euler's conjugate gradients alone, block Jacobi against the grid multigrid
// (sim/linear/block_conjugate_gradient.h, sim/linear/grid_multigrid.h), on the implicit matrix
// of an n×n hanging cloth (tests/support/test_matrices.h) whose springs carry a taut cloth's
// string stiffness: k = 2 N/m × (n − 1) per edge (a tension of 2 N/m over edges 1/(n − 1) m
// long), h = 1/120 s, so h²k/m grows as n³ as it does in the simulation.
//   <preconditioner>/<n>         set_matrix (the multigrid's coarse matrices included) and one
//                                solve from zero to a relative residual of 1e-3;
// counters: CG iterations per solve, and the multigrid's levels (0: block Jacobi).
//
// Run: build/bench/cg_preconditioner_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only

#include <benchmark/benchmark.h>

#include <cmath>

#include "sim/linear/block_conjugate_gradient.h"
#include "tests/support/test_matrices.h"

namespace {

using namespace weft::sim;

void solve(benchmark::State& state, bool multigrid) {
  const auto n = static_cast<Index>(state.range(0));
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(n, 1);
  const SparseMatrix full = test_matrices::implicit_euler_matrix(
      sample, 1.0 / 120.0, 1.0, 2.0 * static_cast<double>(n - 1));
  SparseMatrix lower = full.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  BlockConjugateGradient cg(1);
  cg.analyze(lower, multigrid ? n : 0, multigrid ? n : 0);
  Eigen::VectorXd b(full.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::cos(0.37 * static_cast<double>(i));
  int iterations = 0;
  for (auto _ : state) {
    cg.set_matrix(lower);
    Eigen::VectorXd x;
    iterations = cg.solve(b, x, 1e-3, 1000).iterations;
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["iterations"] = iterations;
  state.counters["levels"] = cg.multigrid_levels();
}

// set_matrix alone: the scatter into blocks, the block inverses and the multigrid's coarse
// matrices (Galerkin products) and coarsest factor.
void set_matrix(benchmark::State& state) {
  const auto n = static_cast<Index>(state.range(0));
  const bool multigrid = state.range(1) != 0;
  const test_matrices::ClothSample sample = test_matrices::make_cloth_sample(n, 1);
  SparseMatrix lower = test_matrices::implicit_euler_matrix(sample).triangularView<Eigen::Lower>();
  lower.makeCompressed();
  BlockConjugateGradient cg(1);
  cg.analyze(lower, multigrid ? n : 0, multigrid ? n : 0);
  for (auto _ : state) cg.set_matrix(lower);
}
BENCHMARK(set_matrix)->ArgsProduct({{64, 128, 256}, {0, 1}})->ArgNames({"n", "multigrid"})->Unit(benchmark::kMillisecond);

void block_jacobi(benchmark::State& state) { solve(state, false); }
void multigrid(benchmark::State& state) { solve(state, true); }
BENCHMARK(block_jacobi)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(multigrid)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace
