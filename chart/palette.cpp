#include "chart/palette.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace weft::chart {

Rgb8 series_colour(std::size_t k) {
  using namespace okabe_ito;
  constexpr std::array<Rgb8, 6> order{vermillion, blue, bluish_green, reddish_purple, orange,
                                      sky_blue};
  return order[k % order.size()];
}

Rgb8 viridis(double t) {
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.0;
  const double u = t * (kViridisStops.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(u), kViridisStops.size() - 2);
  const double f = u - static_cast<double>(i);
  const Rgb8 a = kViridisStops[i], b = kViridisStops[i + 1];
  const auto mix = [f](std::uint8_t p, std::uint8_t q) {
    return static_cast<std::uint8_t>(std::lround(p + f * (q - p)));
  };
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

std::string hex(Rgb8 colour) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", colour.r, colour.g, colour.b);
  return text;
}

}  // namespace weft::chart
