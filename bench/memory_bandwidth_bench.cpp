// The memory speed of this machine and how much of it implicit Euler's block matrix–vector
// product reaches (docs/benchmarks.md, "The implicit step at memory speed"):
//   stream_triad/<threads>        a[i] = b[i] + s·c[i] over three 128 MiB arrays (McCalpin's
//                                 STREAM triad; 24 bytes per element counted, as STREAM does);
//   block_product/n/threads       y = A x of BlockConjugateGradient on the implicit matrix of an
//                                 n×n cloth (tests/support/test_matrices.h), counting the bytes
//                                 it must stream at the least (every block, its column index,
//                                 the row starts, x and y once: bytes_per_product()).
// Both report bytes_per_second; the products also report `of_triad`, their bandwidth over the
// one-thread triad's, measured once at start (median of 7 passes) in the same process.
//
// Run: build/bench/memory_bandwidth_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "base/thread_pool.h"
#include "sim/linear/block_conjugate_gradient.h"
#include "tests/support/test_matrices.h"

namespace {

using namespace weft::sim;

constexpr std::size_t kTriadElements = std::size_t{1} << 24;  // 128 MiB per array

struct TriadArrays {
  std::vector<double> a, b, c;
  TriadArrays() : a(kTriadElements, 0.0), b(kTriadElements, 1.0), c(kTriadElements, 2.0) {}
};

// One pass of the triad over [begin, end).
void triad(TriadArrays& t, std::size_t begin, std::size_t end, double s) {
  double* __restrict a = t.a.data();
  const double* __restrict b = t.b.data();
  const double* __restrict c = t.c.data();
  for (std::size_t i = begin; i < end; ++i) a[i] = b[i] + s * c[i];
}

void triad_pass(TriadArrays& t, weft::base::ThreadPool& pool, std::size_t shares) {
  pool.run(shares, [&](std::size_t share) {
    triad(t, weft::base::share_begin(kTriadElements, shares, share),
          weft::base::share_begin(kTriadElements, shares, share + 1), 3.0);
  });
}

// Bytes a second of the one-thread triad: the median of 7 passes after a warm-up.
double one_thread_triad_bandwidth() {
  static const double bandwidth = [] {
    TriadArrays t;
    weft::base::ThreadPool pool(1);
    triad_pass(t, pool, 1);
    std::vector<double> rates;
    for (int pass = 0; pass < 7; ++pass) {
      const auto start = std::chrono::steady_clock::now();
      triad_pass(t, pool, 1);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      rates.push_back(24.0 * kTriadElements / s);
    }
    std::sort(rates.begin(), rates.end());
    return rates[rates.size() / 2];
  }();
  return bandwidth;
}

void stream_triad(benchmark::State& state) {
  const auto threads = static_cast<std::size_t>(state.range(0));
  TriadArrays t;
  weft::base::ThreadPool pool(static_cast<int>(threads));
  for (auto _ : state) {
    triad_pass(t, pool, threads);
    benchmark::DoNotOptimize(t.a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * 24 *
                          static_cast<std::int64_t>(kTriadElements));
}
BENCHMARK(stream_triad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void block_product(benchmark::State& state) {
  const auto n = static_cast<Index>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const double triad_bandwidth = one_thread_triad_bandwidth();
  const SparseMatrix A =
      test_matrices::implicit_euler_matrix(test_matrices::make_cloth_sample(n, 1));
  BlockConjugateGradient cg(threads);
  cg.analyze(A);
  cg.set_matrix(A);
  Eigen::VectorXd x(A.rows()), y(A.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = std::cos(0.1 * static_cast<double>(i));
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    cg.multiply(x, y);
    benchmark::DoNotOptimize(y.data());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double bytes = static_cast<double>(cg.matrix().bytes_per_product());
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes * static_cast<double>(state.iterations())));
  state.counters["blocks_per_row"] =
      static_cast<double>(cg.matrix().off_diagonal_blocks() + cg.matrix().block_rows()) /
      static_cast<double>(cg.matrix().block_rows());
  state.counters["MB_per_product"] = bytes / 1e6;
  state.counters["of_triad"] =
      bytes * static_cast<double>(state.iterations()) / seconds / triad_bandwidth;
}
BENCHMARK(block_product)
    ->ArgsProduct({{64, 128, 256}, {1, 2}})
    ->ArgNames({"n", "threads"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace
