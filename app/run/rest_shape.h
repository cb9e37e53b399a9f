#pragma once
// A scene's cloth at rest, found by the static equilibrium solver (sim/statics/) instead of by
// simulating its motion: `weft run --rest`, `weft measure --static` and each evaluation of
// `weft fit`. Buckled rest shapes (a Cusick drape's nodes) depend on which branch the solve
// takes; the seed of its imperfection picks one, and several seeds give the spread a real
// fabric's specimens show (docs/measure.md, "Static solves").

#include <memory>
#include <optional>
#include <vector>

#include "analysis/measure/drape_measure.h"
#include "app/scene/scene.h"
#include "sim/simulator.h"

namespace weft::app {

struct RestShape {
  std::unique_ptr<sim::Simulator> simulator;  // holds the rest positions
  sim::StaticResult solve;
  double cpu_s = 0.0;  // the solve's CPU time (this thread's), s
};

// The scene's simulator with its cloth solved to rest from its start, with imperfection seed
// `seed` (the scene's simulation.static.seed when none). Throws InputError naming the scene
// and the setting when the scene cannot be solved statically (sim::static_solve_refusal, a
// moving pin), and as make_simulator.
RestShape solve_rest_shape(const Scene& scene, std::optional<unsigned> seed = std::nullopt);

// A rest shape measured as a drape: DC, folds and outline (with a support), crossings.
struct RestMeasurement {
  unsigned seed = 0;
  sim::StaticResult solve;
  double cpu_s = 0.0;
  std::optional<analysis::DrapeShape> drape;  // with a support under the cloth
  int self_intersections = 0;                 // edge–triangle crossings at rest
};

RestMeasurement measure_rest_shape(const Scene& scene, const RestShape& rest, unsigned seed);

// The spread of a measure over seeds: mean, sample standard deviation, min and max.
struct Spread {
  double mean = 0.0, sd = 0.0, min = 0.0, max = 0.0;
};
Spread spread_of(const std::vector<double>& values);

}  // namespace weft::app
