// The woven check texture and bilinear, repeating texture sampling (see texture.h for the
// mapping of image pixels to material coordinates).

#include "render/texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::render {

namespace {

// Whether fraction-of-period f (in [0, 1)) lies in the band, the first half of the period.
bool in_band(double f) {
  return f < 0.5;
}

double fraction(double x) {
  return x - std::floor(x);
}

std::uint8_t to_byte(float c) {
  return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(c, 0.0f, 1.0f)));
}

}  // namespace

Image make_woven_check(const WovenCheck& check, int size) {
  if (check.stripes < 1 || check.stripes > 64) {
    throw std::invalid_argument("woven check: stripes must be in 1..64, got " +
                                std::to_string(check.stripes));
  }
  if (size < 16 || size > 4096) {
    throw std::invalid_argument("woven check: size must be in 16..4096, got " +
                                std::to_string(size));
  }
  for (const Eigen::Vector3f* c : {&check.warp_color, &check.weft_color, &check.ground_color}) {
    if (!(c->minCoeff() >= 0.0f && c->maxCoeff() <= 1.0f))
      throw std::invalid_argument("woven check: colours must be in [0, 1]");
  }
  Image image(size, size);
  constexpr int threads_per_band = 8;
  for (int y = 0; y < size; ++y) {
    const double t = 1.0 - (y + 0.5) / size;  // weft coordinate of the row, one repeat = 1
    for (int x = 0; x < size; ++x) {
      const double s = (x + 0.5) / size;  // warp coordinate of the column
      const double ft = fraction(t * check.stripes), fs = fraction(s * check.stripes);
      const bool warp = in_band(ft), weft = in_band(fs);
      Eigen::Vector3f c = check.ground_color;
      if (warp && weft)
        c = 0.5f * (check.warp_color + check.weft_color);
      else if (warp)
        c = check.warp_color;
      else if (weft)
        c = check.weft_color;
      // Thread lines: warp threads run along s, so their gaps are lines of constant t, and
      // weft threads' gaps lines of constant s. One thread is 1 / (2 · 8) of a period wide.
      const double thread =
          warp ? fraction(ft * 2.0 * threads_per_band) : fraction(fs * 2.0 * threads_per_band);
      if ((warp || weft) && thread > 0.8) c *= 0.8f;
      image.set(x, y, {to_byte(c.x()), to_byte(c.y()), to_byte(c.z())});
    }
  }
  return image;
}

TexturePlacement texture_placement(const ClothTexture& texture,
                                   const std::vector<Eigen::Vector2f>& uvs) {
  TexturePlacement placement;
  if (texture.mapping == TextureMapping::repeat || uvs.empty()) {
    placement.size = texture.repeat_m.cast<float>();
    return placement;
  }
  Eigen::Vector2f lo = uvs.front(), hi = uvs.front();
  for (const Eigen::Vector2f& uv : uvs) {
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
  }
  placement.origin = lo;
  placement.size = hi - lo;
  for (int k = 0; k < 2; ++k) {
    if (!(placement.size[k] > 0.0f)) placement.size[k] = 1.0f;
  }
  placement.repeat = false;
  return placement;
}

Eigen::Vector3f sample_texture(const Image& image, float s, float t, bool repeat) {
  const int w = image.width(), h = image.height();
  // Continuous pixel coordinates with pixel centres at integers + 0.5: wrapped into one
  // repeat, or clamped to the centres of the edge texels.
  float px = s * static_cast<float>(w) - 0.5f;
  float py = (1.0f - t) * static_cast<float>(h) - 0.5f;
  if (!std::isfinite(px) || !std::isfinite(py)) return Eigen::Vector3f::Zero();
  if (repeat) {
    px -= static_cast<float>(w) * std::floor(px / static_cast<float>(w));
    py -= static_cast<float>(h) * std::floor(py / static_cast<float>(h));
  } else {
    px = std::clamp(px, 0.0f, static_cast<float>(w - 1));
    py = std::clamp(py, 0.0f, static_cast<float>(h - 1));
  }
  const int x0 = std::min(static_cast<int>(px), w - 1), y0 = std::min(static_cast<int>(py), h - 1);
  const int x1 = repeat ? (x0 + 1) % w : std::min(x0 + 1, w - 1);
  const int y1 = repeat ? (y0 + 1) % h : std::min(y0 + 1, h - 1);
  const float ax = std::clamp(px - static_cast<float>(x0), 0.0f, 1.0f);
  const float ay = std::clamp(py - static_cast<float>(y0), 0.0f, 1.0f);
  const auto texel = [&](int x, int y) {
    const Rgb8 p = image.at(x, y);
    constexpr float scale = 1.0f / 255.0f;
    return Eigen::Vector3f(scale * static_cast<float>(p.r), scale * static_cast<float>(p.g),
                           scale * static_cast<float>(p.b));
  };
  return (1.0f - ay) * ((1.0f - ax) * texel(x0, y0) + ax * texel(x1, y0)) +
         ay * ((1.0f - ax) * texel(x0, y1) + ax * texel(x1, y1));
}

}  // namespace weft::render
