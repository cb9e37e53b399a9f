// The plain weave's normal map (see weave.h).

#include "render/weave.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/constants.h"
#include "render/texture.h"

namespace weft::render {
namespace {

// Height (0..1) of the weave at (s, t) in one repeat [0, 1)²: two warp threads stacked along
// t (each a band of height 1/2), two weft threads side by side along s. A thread's cross
// section is a rounded ridge, sqrt(sin); along its length it rises over one crossing thread
// and dips under the next, cos; the higher of the two threads at a point is seen.
double weave_height(double s, double t) {
  const auto ridge = [](double across) { return std::sqrt(std::max(0.0, std::sin(base::kPi * across))); };
  const double warp_index = std::floor(2.0 * t), weft_index = std::floor(2.0 * s);
  const double across_warp = 2.0 * t - warp_index, across_weft = 2.0 * s - weft_index;
  // Warp thread k is over weft thread m where k + m is even: its crest at the middle of that
  // weft thread, s = (m + 1/2)/2.
  const double warp = ridge(across_warp) *
                      (0.5 + 0.5 * std::cos(2.0 * base::kPi * s + base::kPi * (warp_index + 0.5)));
  const double weft = ridge(across_weft) *
                      (0.5 + 0.5 * std::cos(2.0 * base::kPi * t + base::kPi * (weft_index + 1.5)));
  return std::max(warp, weft);
}

}  // namespace

Image make_weave_normal_map(int size) {
  if (size < 8 || size > 1024)
    throw std::invalid_argument("weave normal map: size must be in 8..1024, got " +
                                std::to_string(size));
  // Heights at texel centres, then the normal of the height field h · relief (in repeat units)
  // by central differences, wrapping around the repeat.
  constexpr double relief = 0.25;  // thread height against the repeat's width at depth 1
  std::vector<double> h(static_cast<std::size_t>(size) * size);
  const auto at = [&](int x, int y) -> double& {
    return h[static_cast<std::size_t>((y + size) % size) * size + (x + size) % size];
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      at(x, y) = weave_height((x + 0.5) / size, 1.0 - (y + 0.5) / size);  // row 0 the top
  Image map(size, size);
  const double step = 2.0 / size;  // the central difference's span, in repeats
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double dh_ds = relief * (at(x + 1, y) - at(x - 1, y)) / step;
      const double dh_dt = relief * (at(x, y - 1) - at(x, y + 1)) / step;  // t grows upwards
      const Eigen::Vector3d n = Eigen::Vector3d(-dh_ds, -dh_dt, 1.0).normalized();
      const auto byte = [](double c) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(127.5 * (c + 1.0)), 0L, 255L));
      };
      map.set(x, y, {byte(n.x()), byte(n.y()), byte(n.z())});
    }
  }
  return map;
}

Eigen::Vector3f weave_normal(const Image& map, float s, float t, float depth) {
  const Eigen::Vector3f c = sample_texture(map, s, t, true);
  Eigen::Vector3f m = 2.0f * c - Eigen::Vector3f::Ones();
  m.x() *= depth;
  m.y() *= depth;
  const float length = m.norm();
  return length > 0.0f ? Eigen::Vector3f(m / length) : Eigen::Vector3f::UnitZ();
}

Eigen::Vector3f tilt_normal(const Eigen::Vector3f& n, const Eigen::Vector3f& t_warp,
                            const Eigen::Vector3f& t_weft, const Eigen::Vector3f& m) {
  Eigen::Vector3f t = t_warp - n.dot(t_warp) * n;
  if (!(t.norm() > 1e-12f)) return n;
  t.normalize();
  Eigen::Vector3f b = n.cross(t);
  if (b.dot(t_weft) < 0.0f) b = -b;  // the weft's side
  const Eigen::Vector3f tilted = m.x() * t + m.y() * b + m.z() * n;
  const float length = tilted.norm();
  return length > 0.0f && tilted.allFinite() ? Eigen::Vector3f(tilted / length) : n;
}

}  // namespace weft::render
