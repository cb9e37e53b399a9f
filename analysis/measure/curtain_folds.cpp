// Folds of a hanging curtain down its centre column; see curtain_folds.h.

#include "analysis/measure/curtain_folds.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::analysis {

int count_alternating_extremes(const std::vector<double>& values, double min_prominence) {
  if (!(min_prominence > 0.0))
    throw std::invalid_argument("count_alternating_extremes: min_prominence must be > 0");
  if (values.empty()) return 0;
  int extremes = 0;
  int direction = 0;  // +1 rising towards a maximum, −1 falling towards a minimum, 0 not yet
  double start = values.front(), candidate = values.front();
  for (const double v : values) {
    if (direction == 0) {
      if (std::abs(v - start) >= min_prominence) {
        extremes = 1;  // the start, which the offset has left by the hysteresis
        direction = v > start ? 1 : -1;
        candidate = v;
      }
    } else if (direction * (v - candidate) > 0.0) {
      candidate = v;  // still going the same way
    } else if (direction * (candidate - v) >= min_prominence) {
      ++extremes;  // the candidate was an extreme: the offset came back from it far enough
      direction = -direction;
      candidate = v;
    }
  }
  return direction == 0 ? 0 : extremes + 1;  // the last run's end is an extreme too
}

CurtainFolds count_curtain_folds(const sim::ClothMesh& mesh, const sim::Matrix3X& x,
                                 double prominence_fraction, double min_prominence_m) {
  mesh.require_grid("counting curtain folds (down the grid's centre column)");
  if (mesh.nu < 2 || mesh.nv < 2)
    throw std::invalid_argument("count_curtain_folds: the grid needs at least 2 × 2 vertices");
  if (x.rows() != mesh.vertex_count())
    throw std::invalid_argument("count_curtain_folds: expected " +
                                std::to_string(mesh.vertex_count()) + " positions, got " +
                                std::to_string(x.rows()));
  const sim::Vec3 left = x.row(mesh.index(0, 0)).transpose();
  const sim::Vec3 right = x.row(mesh.index(mesh.nu - 1, 0)).transpose();
  const sim::Vec3 rest_warp = (mesh.rest_positions.row(mesh.index(mesh.nu - 1, 0)) -
                               mesh.rest_positions.row(mesh.index(0, 0)))
                                  .transpose();
  const sim::Vec3 rest_weft = (mesh.rest_positions.row(mesh.index(0, mesh.nv - 1)) -
                               mesh.rest_positions.row(mesh.index(0, 0)))
                                  .transpose();
  // The supports' plane: through both top corners, containing the (rest) weft direction.
  sim::Vec3 across = right - left;
  if (!(across.norm() > 0.0)) across = rest_warp;
  const sim::Vec3 normal = across.cross(rest_weft).normalized();
  CurtainFolds out;
  const sim::Index column = (mesh.nu - 1) / 2;
  for (sim::Index j = 0; j < mesh.nv; ++j)
    out.offsets_m.push_back((x.row(mesh.index(column, j)).transpose() - left).dot(normal));
  const auto [lo, hi] = std::minmax_element(out.offsets_m.begin(), out.offsets_m.end());
  out.min_prominence_m = std::max(prominence_fraction * (*hi - *lo), min_prominence_m);
  out.folds = count_alternating_extremes(out.offsets_m, out.min_prominence_m);
  return out;
}

}  // namespace weft::analysis
