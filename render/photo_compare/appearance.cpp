// Masked SSIM and CIEDE2000 colour difference; see appearance.h.

#include "render/photo_compare/appearance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"
#include "render/image_diff.h"

namespace weft::render {
namespace {

constexpr int kSsimRadius = 5;  // the 11 × 11 window of image_diff.h

double srgb_to_linear(double v) {  // v in [0, 1]
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double lab_f(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

double to_degrees(double radians) {
  return radians * 180.0 / base::kPi;
}
double to_radians(double degrees_) {
  return degrees_ * base::kPi / 180.0;
}

// h' of CIEDE2000: atan2(b, a') in [0°, 360°), 0 for a neutral colour.
double hue_degrees(double b, double a_prime) {
  if (b == 0.0 && a_prime == 0.0) return 0.0;
  const double h = to_degrees(std::atan2(b, a_prime));
  return h < 0.0 ? h + 360.0 : h;
}

void check_mask_size(int w, int h, const Mask& mask, const char* what) {
  if (mask.width != w || mask.height != h)
    throw std::invalid_argument(std::string(what) + ": the mask is " + std::to_string(mask.width) +
                                "x" + std::to_string(mask.height) + ", the images " +
                                std::to_string(w) + "x" + std::to_string(h));
}

}  // namespace

Lab srgb_to_lab(Rgb8 c) {
  const double r = srgb_to_linear(c.r / 255.0), g = srgb_to_linear(c.g / 255.0),
               b = srgb_to_linear(c.b / 255.0);
  // IEC 61966-2-1's sRGB → XYZ (D65).
  const double x = 0.4124 * r + 0.3576 * g + 0.1805 * b;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
  const double fx = lab_f(x / 0.9505), fy = lab_f(y), fz = lab_f(z / 1.0890);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ciede2000(const Lab& p, const Lab& q) {
  const double c1 = std::hypot(p[1], p[2]), c2 = std::hypot(q[1], q[2]);
  const double c_mean = 0.5 * (c1 + c2);
  const double c7 = std::pow(c_mean, 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(c7 / (c7 + std::pow(25.0, 7.0))));
  const double a1 = (1.0 + g) * p[1], a2 = (1.0 + g) * q[1];
  const double cp1 = std::hypot(a1, p[2]), cp2 = std::hypot(a2, q[2]);
  const double h1 = hue_degrees(p[2], a1), h2 = hue_degrees(q[2], a2);
  const double dl = q[0] - p[0], dc = cp2 - cp1;
  double dh = 0.0;  // Δh', degrees
  if (cp1 * cp2 != 0.0) {
    dh = h2 - h1;
    if (dh > 180.0)
      dh -= 360.0;
    else if (dh < -180.0)
      dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(to_radians(dh / 2.0));
  const double l_mean = 0.5 * (p[0] + q[0]), cp_mean = 0.5 * (cp1 + cp2);
  double h_mean = h1 + h2;  // mean hue h̄', degrees
  if (cp1 * cp2 != 0.0) {
    if (std::abs(h1 - h2) <= 180.0)
      h_mean = 0.5 * (h1 + h2);
    else
      h_mean = h1 + h2 < 360.0 ? 0.5 * (h1 + h2 + 360.0) : 0.5 * (h1 + h2 - 360.0);
  }
  const double t = 1.0 - 0.17 * std::cos(to_radians(h_mean - 30.0)) +
                   0.24 * std::cos(to_radians(2.0 * h_mean)) +
                   0.32 * std::cos(to_radians(3.0 * h_mean + 6.0)) -
                   0.20 * std::cos(to_radians(4.0 * h_mean - 63.0));
  const double d_theta = 30.0 * std::exp(-std::pow((h_mean - 275.0) / 25.0, 2.0));
  const double cp7 = std::pow(cp_mean, 7.0);
  const double rc = 2.0 * std::sqrt(cp7 / (cp7 + std::pow(25.0, 7.0)));
  const double l50 = (l_mean - 50.0) * (l_mean - 50.0);
  const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sc = 1.0 + 0.045 * cp_mean, sh = 1.0 + 0.015 * cp_mean * t;
  const double rt = -std::sin(to_radians(2.0 * d_theta)) * rc;
  const double tl = dl / sl, tc = dc / sc, th = dH / sh;
  return std::sqrt(tl * tl + tc * tc + th * th + rt * tc * th);
}

std::optional<MaskedSsim> masked_ssim(const std::vector<double>& photo,
                                      const std::vector<double>& render, int w, int h,
                                      const Mask& mask) {
  check_mask_size(w, h, mask, "masked SSIM");
  const Mask centres = eroded_mask(mask, kSsimRadius);
  if (moments(centres).area_px <= 0) return std::nullopt;
  const std::vector<double> map = ssim_map(photo, render, w, h);
  const int mw = w - 2 * kSsimRadius;
  MaskedSsim s;
  double sum = 0.0;
  for (int y = kSsimRadius; y < h - kSsimRadius; ++y)
    for (int x = kSsimRadius; x < w - kSsimRadius; ++x)
      if (centres.at(x, y)) {
        sum += map[static_cast<std::size_t>(y - kSsimRadius) * mw + (x - kSsimRadius)];
        ++s.windows;
      }
  s.mean = sum / static_cast<double>(s.windows);
  return s;
}

ColourDifference mask_colour_difference(const Image& photo, const Image& render, const Mask& mask) {
  const int w = photo.width(), h = photo.height();
  if (render.width() != w || render.height() != h)
    throw std::invalid_argument("colour difference: the images are " + std::to_string(w) + "x" +
                                std::to_string(h) + " and " + std::to_string(render.width()) + "x" +
                                std::to_string(render.height()));
  check_mask_size(w, h, mask, "colour difference");
  std::vector<double> de;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (mask.at(x, y))
        de.push_back(ciede2000(srgb_to_lab(photo.at(x, y)), srgb_to_lab(render.at(x, y))));
  if (de.empty()) throw std::invalid_argument("colour difference: the mask is empty");
  ColourDifference d;
  d.pixels = static_cast<long>(de.size());
  double sum = 0.0;
  for (const double v : de) sum += v;
  d.mean = sum / static_cast<double>(de.size());
  // Nearest rank: the smallest value with at least 95 % of the values at or below it.
  const std::size_t rank =
      static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(de.size())));
  const auto nth = de.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
  std::nth_element(de.begin(), nth, de.end());
  d.p95 = *nth;
  return d;
}

}  // namespace weft::render
