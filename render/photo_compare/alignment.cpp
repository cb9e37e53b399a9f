// Silhouette alignment and resampling; see alignment.h.

#include "render/photo_compare/alignment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace weft::render {
namespace {

// Calls sample(rx, ry) at the n × n render points that photo pixel (x, y) covers, and returns n².
template <typename Sample>
int for_each_subsample(const Similarity& t, int x, int y, Sample&& sample) {
  const int n = std::max(1, static_cast<int>(std::ceil(1.0 / t.scale - 1e-9)));
  const double c = std::cos(t.angle_rad), s = std::sin(t.angle_rad);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double px = x + (i + 0.5) / n - 0.5 - t.tx_px, py = y + (j + 0.5) / n - 0.5 - t.ty_px;
      // r = R(−θ) (p − t) / s
      sample((c * px + s * py) / t.scale, (-s * px + c * py) / t.scale);
    }
  return n * n;
}

void check_scale(const Similarity& t) {
  if (!(t.scale > 0.0) || !std::isfinite(t.scale))
    throw std::invalid_argument("alignment: the scale must be positive, got " +
                                std::to_string(t.scale));
}

}  // namespace

Similarity align_silhouettes(const Mask& photo, const Mask& render) {
  const SilhouetteMoments p = moments(photo), r = moments(render);
  if (p.area_px <= 0.0 || r.area_px <= 0.0)
    throw std::invalid_argument("alignment: a silhouette is empty");
  Similarity t;
  t.scale = std::sqrt(p.area_px / r.area_px);
  t.tx_px = p.cx - t.scale * r.cx;
  t.ty_px = p.cy - t.scale * r.cy;
  return t;
}

Image warp_image(const Image& render, const Similarity& t, int width, int height) {
  check_scale(t);
  Image out(width, height);
  const int w = render.width(), h = render.height();
  const auto pixel = [&](int x, int y) {
    return render.at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1));
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::array<double, 3> sum{};
      const int n = for_each_subsample(t, x, y, [&](double rx, double ry) {
        const int x0 = static_cast<int>(std::floor(rx)), y0 = static_cast<int>(std::floor(ry));
        const double fx = rx - x0, fy = ry - y0;
        const Rgb8 q[4] = {pixel(x0, y0), pixel(x0 + 1, y0), pixel(x0, y0 + 1), pixel(x0 + 1, y0 + 1)};
        const double wt[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        for (int k = 0; k < 4; ++k) {
          sum[0] += wt[k] * q[k].r;
          sum[1] += wt[k] * q[k].g;
          sum[2] += wt[k] * q[k].b;
        }
      });
      const auto byte = [&](double v) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(v / n), 0L, 255L));
      };
      out.set(x, y, {byte(sum[0]), byte(sum[1]), byte(sum[2])});
    }
  return out;
}

Mask warp_mask(const Mask& render, const Similarity& t, int width, int height) {
  check_scale(t);
  Mask out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double cover = 0.0;
      const int n = for_each_subsample(t, x, y, [&](double rx, double ry) {
        const int x0 = static_cast<int>(std::floor(rx)), y0 = static_cast<int>(std::floor(ry));
        const double fx = rx - x0, fy = ry - y0;
        cover += (1 - fx) * (1 - fy) * render.at_or_out(x0, y0) +
                 fx * (1 - fy) * render.at_or_out(x0 + 1, y0) +
                 (1 - fx) * fy * render.at_or_out(x0, y0 + 1) + fx * fy * render.at_or_out(x0 + 1, y0 + 1);
      });
      out.set(x, y, cover >= 0.5 * n);
    }
  return out;
}

}  // namespace weft::render
