// Cost of one mass-spring step (forces + symplectic Euler + divergence check) by resolution.
#include <benchmark/benchmark.h>

#include "sim/pins.h"
#include "sim/simulator.h"

namespace {

using namespace weft::sim;

Simulator hanging_cloth(Index n) {
  GridSpec spec;
  spec.nu = spec.nv = n;
  const ClothMesh mesh = make_grid(spec);
  Material wool;  // the defaults: Kang & Yu wool (seed 002)
  return Simulator(mesh, wool, resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), SimSettings{});
}

void BM_MassSpringStep(benchmark::State& state) {
  const auto n = static_cast<Index>(state.range(0));
  Simulator sim = hanging_cloth(n);
  sim.advance(0.05);  // get it moving: forces everywhere non-zero
  const double h = sim.time_step();
  for (auto _ : state) sim.step(h);
  const double vertices = static_cast<double>(n) * static_cast<double>(n);
  state.counters["vertices"] = vertices;
  // Seconds per vertex per step (printed with an SI prefix, e.g. 130n = 130 ns).
  state.counters["s_per_vertex_step"] = benchmark::Counter(
      vertices * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_MassSpringStep)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

}  // namespace
