// Cost of the per-frame self-intersection count (sim/collision/self_intersection.h) by
// resolution, on a 1 m sheet folded into smooth waves with small random wrinkles (no crossings:
// the common case in stats.csv), and on a crumpled one (many crossings). Compare with a frame's
// sim_ms in stats.csv (one frame is many steps; BM_MassSpringStep in sim_bench is one step).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "sim/collision/self_intersection.h"
#include "sim/grid.h"

namespace {

using namespace weft::sim;

Matrix3X wavy_sheet(const ClothMesh& mesh, double noise_m, unsigned seed) {
  Matrix3X x = mesh.rest_positions;
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> noise(-noise_m, noise_m);
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    x(v, 2) += 0.1 * std::sin(12.0 * x(v, 0)) * std::cos(8.0 * x(v, 1));
    for (int k = 0; k < 3; ++k) x(v, k) += noise(generator);
  }
  return x;
}

void run(benchmark::State& state, double noise_in_spacings) {
  GridSpec spec;
  spec.nu = spec.nv = static_cast<Index>(state.range(0));
  const ClothMesh mesh = make_grid(spec);
  const auto triangles = mesh.triangles();
  const auto edges = unique_edges(triangles);
  const Matrix3X x = wavy_sheet(mesh, noise_in_spacings / (spec.nu - 1), 1);
  Index crossings = 0;
  for (auto _ : state) benchmark::DoNotOptimize(crossings = count_edge_triangle_crossings(x, triangles, edges));
  state.counters["crossings"] = crossings;
  state.counters["triangles"] = static_cast<double>(triangles.size());
}

void BM_SelfIntersectionSmooth(benchmark::State& state) { run(state, 0.1); }
void BM_SelfIntersectionCrumpled(benchmark::State& state) { run(state, 1.5); }
BENCHMARK(BM_SelfIntersectionSmooth)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SelfIntersectionCrumpled)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);

}  // namespace
