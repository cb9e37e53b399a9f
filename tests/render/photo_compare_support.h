#pragma once
// Synthetic "photos" for the photo-comparison tests: a procedurally drawn curtain (a trapezoid
// of red cloth whose shading varies as cos(2π n u / width), n sinusoidal folds) on a plain
// background, drawn with 4 × 4 supersampling so that sub-pixel shifts and scales show, and the
// perturbations a photo brings: blur, noise, a colour cast.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "base/constants.h"
#include "render/image.h"

namespace weft::render::test {

struct CurtainSpec {
  int width = 200, height = 150;
  double cx = 100, cy = 75;     // centre of the cloth, pixels
  double scale = 1.0;           // cloth size factor
  int folds = 5;                // fold periods across the cloth
  Rgb8 background{70, 90, 110};
  Rgb8 cloth{210, 70, 55};
};

// The cloth in its own units (scale 1): 80 px tall, 60 px wide at the top widening to 76.
inline bool curtain_inside(double u, double v) {
  return v >= -40 && v <= 40 && std::abs(u) <= 30 + 0.1 * (v + 40);
}

inline Image draw_curtain(const CurtainSpec& s) {
  Image image(s.width, s.height);
  constexpr int n = 4;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double r = 0, g = 0, b = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double u = (x + (i + 0.5) / n - 0.5 - s.cx) / s.scale;
          const double v = (y + (j + 0.5) / n - 0.5 - s.cy) / s.scale;
          if (curtain_inside(u, v)) {
            const double shade = 0.65 + 0.35 * std::cos(2 * base::kPi * s.folds * u / 60.0);
            r += shade * s.cloth.r;
            g += shade * s.cloth.g;
            b += shade * s.cloth.b;
          } else {
            r += s.background.r;
            g += s.background.g;
            b += s.background.b;
          }
        }
      const auto byte = [](double c) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(c / (n * n)), 0L, 255L));
      };
      image.set(x, y, {byte(r), byte(g), byte(b)});
    }
  return image;
}

// A 3 × 3 binomial blur applied `passes` times (σ ≈ 0.71 px per pass), edges clamped.
inline Image blurred(const Image& in, int passes) {
  Image img = in;
  const int w = img.width(), h = img.height();
  for (int p = 0; p < passes; ++p) {
    Image out(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double c[3] = {0, 0, 0};
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const double k = (dx == 0 ? 2 : 1) * (dy == 0 ? 2 : 1) / 16.0;
            const Rgb8 q = img.at(std::clamp(x + dx, 0, w - 1), std::clamp(y + dy, 0, h - 1));
            c[0] += k * q.r;
            c[1] += k * q.g;
            c[2] += k * q.b;
          }
      out.set(x, y, {static_cast<std::uint8_t>(std::lround(c[0])), static_cast<std::uint8_t>(std::lround(c[1])),
                     static_cast<std::uint8_t>(std::lround(c[2]))});
      }
    img = out;
  }
  return img;
}

// Adds uniform noise of ±amplitude grey levels, from a fixed per-pixel hash (deterministic).
inline Image noisy(const Image& in, int amplitude) {
  Image out = in;
  for (int y = 0; y < in.height(); ++y)
    for (int x = 0; x < in.width(); ++x) {
      std::uint32_t hsh = static_cast<std::uint32_t>(x) * 73856093u ^ static_cast<std::uint32_t>(y) * 19349663u ^ 0x9e3779b9u;
      const auto next = [&] {
        hsh ^= hsh << 13;
        hsh ^= hsh >> 17;
        hsh ^= hsh << 5;
        return static_cast<int>(hsh % static_cast<std::uint32_t>(2 * amplitude + 1)) - amplitude;
      };
      const Rgb8 p = in.at(x, y);
      const auto add = [&](std::uint8_t c) { return static_cast<std::uint8_t>(std::clamp(c + next(), 0, 255)); };
      out.set(x, y, {add(p.r), add(p.g), add(p.b)});
    }
  return out;
}

// Multiplies each channel by its factor (a white-balance error).
inline Image colour_cast(const Image& in, double r, double g, double b) {
  Image out = in;
  for (int y = 0; y < in.height(); ++y)
    for (int x = 0; x < in.width(); ++x) {
      const Rgb8 p = in.at(x, y);
      const auto f = [](std::uint8_t c, double k) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(c * k), 0L, 255L));
      };
      out.set(x, y, {f(p.r, r), f(p.g, g), f(p.b, b)});
    }
  return out;
}

}  // namespace weft::render::test
