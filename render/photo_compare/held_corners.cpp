// The held corners of a hanging cloth in its mask; see held_corners.h.

#include "render/photo_compare/held_corners.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/photo_compare/silhouette.h"

namespace weft::render {
namespace {

// The mean of the mask pixels whose score s(u, v) lies within ½ of the smallest.
template <class Score>
Eigen::Vector2d extremal_point(const Mask& m, Score score) {
  double best = std::numeric_limits<double>::infinity();
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      if (m.at(x, y)) best = std::min(best, score(x, y));
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double n = 0.0;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      if (m.at(x, y) && score(x, y) <= best + 0.5) {
        sum += Eigen::Vector2d(x, y);
        n += 1.0;
      }
  return sum / n;
}

}  // namespace

HeldCorners find_held_corners(const Mask& mask, double k) {
  HeldCorners c;
  const Mask filled = fill_holes(largest_component(mask));
  const double area = moments(filled).area_px;
  if (area <= 0) throw std::invalid_argument("held corners: the mask has no cloth pixel");
  c.opening_radius_px = std::max(1, static_cast<int>(std::lround(0.01 * std::sqrt(area))));
  c.cleaned = dilated_mask(eroded_mask(filled, c.opening_radius_px), c.opening_radius_px);
  if (moments(c.cleaned).area_px <= 0) c.cleaned = filled;  // thinner than the opening
  c.px[0] = extremal_point(c.cleaned, [k](int x, int y) { return y + k * x; });
  c.px[1] = extremal_point(c.cleaned, [k](int x, int y) { return y - k * x; });
  if ((c.px[1] - c.px[0]).norm() < 1.0)
    throw std::invalid_argument(
        "held corners: the top-left and top-right corners of the mask "
        "fall on one pixel (is it a cloth held by two corners?)");
  return c;
}

}  // namespace weft::render
