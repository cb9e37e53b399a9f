#include "app/run/rest_shape.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <numeric>
#include <stdexcept>

#include "app/io/input_error.h"
#include "app/run/measure.h"
#include "sim/collision/self_intersection.h"

namespace weft::app {

RestShape solve_rest_shape(const Scene& scene, std::optional<unsigned> seed) {
  if (const std::string why = sim::static_solve_refusal(scene.sim); !why.empty())
    throw InputError(scene.source + ": " + why);
  RestShape rest;
  rest.simulator = make_simulator(scene);
  sim::StaticSettings settings = scene.sim.statics;
  if (seed) settings.seed = *seed;
  const std::clock_t start = std::clock();
  try {
    rest.solve = rest.simulator->solve_static(settings);
  } catch (const std::invalid_argument& e) {  // moving pins: the scene's, so bad input
    throw InputError(scene.source + ": " + e.what());
  }
  rest.cpu_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  return rest;
}

RestMeasurement measure_rest_shape(const Scene& scene, const RestShape& rest, unsigned seed) {
  RestMeasurement m;
  m.seed = seed;
  m.solve = rest.solve;
  m.cpu_s = rest.cpu_s;
  const sim::Simulator& simulator = *rest.simulator;
  const sim::ClothMesh& mesh = simulator.mesh();
  const auto triangles = mesh.triangles();
  if (const auto support = scene_support(scene, mesh, false))
    m.drape = analysis::measure_drape(mesh, triangles, simulator.state().x, *support);
  m.self_intersections = sim::count_edge_triangle_crossings(simulator.state().x, triangles,
                                                            sim::unique_edges(triangles));
  return m;
}

Spread spread_of(const std::vector<double>& values) {
  Spread s;
  if (values.empty()) return s;
  const double n = static_cast<double>(values.size());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  double ss = 0.0;
  for (const double v : values) ss += (v - s.mean) * (v - s.mean);
  s.sd = values.size() > 1 ? std::sqrt(ss / (n - 1.0)) : 0.0;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  s.min = *lo;
  s.max = *hi;
  return s;
}

}  // namespace weft::app
