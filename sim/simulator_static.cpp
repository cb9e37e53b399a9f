// Simulator::solve_static (simulator.h): the cloth moved to its static equilibrium.

#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <stdexcept>

#include "sim/simulator.h"
#include "sim/statics/static_equilibrium.h"

namespace weft::sim {
namespace {

// The mean and the shortest rest length of the cloth's triangle edges, m.
std::pair<double, double> rest_edge_lengths(const ClothMesh& mesh) {
  double sum = 0.0, shortest = std::numeric_limits<double>::infinity();
  long count = 0;
  for (const auto& t : mesh.triangles())
    for (int k = 0; k < 3; ++k) {
      const double l = (mesh.rest_positions.row(t[k]) - mesh.rest_positions.row(t[(k + 1) % 3])).norm();
      sum += l;
      shortest = std::min(shortest, l);
      ++count;
    }
  if (count == 0) throw std::invalid_argument("a static solve needs a cloth with triangles");
  return {sum / static_cast<double>(count), shortest};
}

}  // namespace

std::string static_solve_refusal(const SimSettings& s) {
  if (s.projection.method != ProjectionMethod::none)
    return "simulation.constraints: a static solve needs the cloth's stretch as springs, not "
           "constraints (projection '" + std::string(base::enum_name(projection_method_names, s.projection.method)) + "')";
  if (any_moves(s.obstacle_motions))
    return "obstacles move: a static solve needs still obstacles";
  if (s.aero.enabled) return "simulation.air: drag and wind have no static potential";
  if (s.remesh.enabled) return "simulation.remesh: a static solve keeps the scene's mesh";
  return "";
}

StaticResult Simulator::solve_static(const StaticSettings& settings) {
  if (const std::string why = static_solve_refusal(m_settings); !why.empty())
    throw std::invalid_argument(why);
  if (!m_moving_pins.empty()) throw std::invalid_argument("pins move: a static solve needs still pins");
  const auto [mean_edge, shortest_edge] = rest_edge_lengths(m_mesh);
  const StaticEquilibrium statics(m_system, m_settings.obstacles, m_settings.collision_thickness_m,
                                  mean_edge, shortest_edge, settings);
  const StaticResult result = statics.solve(m_state.x);
  m_state.v.setZero();
  check_finite();
  return result;
}

}  // namespace weft::sim
