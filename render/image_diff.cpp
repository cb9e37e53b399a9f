// Image comparison; the metrics are defined in image_diff.h.

#include "render/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <vector>

namespace weft::render {
namespace {

constexpr int window = 11;
constexpr double window_sigma = 1.5;

void check_sizes(const Image& a, const Image& b) {
  if (a.width() <= 0 || a.height() <= 0 || b.width() <= 0 || b.height() <= 0)
    throw std::invalid_argument("image comparison: an image is empty");
  if (a.width() != b.width() || a.height() != b.height())
    throw std::invalid_argument("image sizes differ: " + std::to_string(a.width()) + "x" +
                                std::to_string(a.height()) + " and " + std::to_string(b.width()) +
                                "x" + std::to_string(b.height()));
}

// The 1-D factor of the separable Gaussian window, normalised to sum 1.
std::array<double, window> gaussian_taps() {
  std::array<double, window> g{};
  double sum = 0.0;
  for (int k = 0; k < window; ++k) {
    const double x = k - window / 2;
    g[static_cast<std::size_t>(k)] = std::exp(-x * x / (2.0 * window_sigma * window_sigma));
    sum += g[static_cast<std::size_t>(k)];
  }
  for (double& v : g) v /= sum;
  return g;
}

// 'valid' separable filtering of v (w × h) with the window: (w − 10) × (h − 10) values.
std::vector<double> filter_valid(const std::vector<double>& v, int w, int h) {
  static const std::array<double, window> g = gaussian_taps();
  const int ow = w - window + 1, oh = h - window + 1;
  std::vector<double> rows(static_cast<std::size_t>(ow) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int k = 0; k < window; ++k)
        s += g[static_cast<std::size_t>(k)] * v[static_cast<std::size_t>(y) * w + x + k];
      rows[static_cast<std::size_t>(y) * ow + x] = s;
    }
  std::vector<double> out(static_cast<std::size_t>(ow) * static_cast<std::size_t>(oh));
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int k = 0; k < window; ++k)
        s += g[static_cast<std::size_t>(k)] * rows[static_cast<std::size_t>(y + k) * ow + x];
      out[static_cast<std::size_t>(y) * ow + x] = s;
    }
  return out;
}

double ssim_term(double mx, double my, double vx, double vy, double cxy) {
  constexpr double c1 = (0.01 * 255.0) * (0.01 * 255.0), c2 = (0.03 * 255.0) * (0.03 * 255.0);
  return ((2.0 * mx * my + c1) * (2.0 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
}

Rgb8 heat_ramp(double t) {  // t in [0, 1]: black → blue → red → yellow → white
  static const double stops[5][3] = {{0, 0, 0}, {0, 0, 255}, {255, 0, 0}, {255, 255, 0}, {255, 255, 255}};
  const double s = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  const auto mix = [&](int c) {
    return static_cast<std::uint8_t>(std::lround(stops[i][c] + f * (stops[i + 1][c] - stops[i][c])));
  };
  return {mix(0), mix(1), mix(2)};
}

}  // namespace

std::vector<double> luminance(const Image& image) {
  std::vector<double> y;
  y.reserve(static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
  for (int r = 0; r < image.height(); ++r)
    for (int c = 0; c < image.width(); ++c) {
      const Rgb8 p = image.at(c, r);
      y.push_back(0.299 * p.r + 0.587 * p.g + 0.114 * p.b);
    }
  return y;
}

double ssim(const std::vector<double>& a, const std::vector<double>& b, int width, int height) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (width <= 0 || height <= 0 || a.size() != n || b.size() != n)
    throw std::invalid_argument("ssim: expected two " + std::to_string(width) + "x" +
                                std::to_string(height) + " luminance images");
  if (width < window || height < window) {  // one window of equal weights
    const double count = static_cast<double>(n);
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
    ma /= count, mb /= count;
    double va = 0, vb = 0, cab = 0;
    for (std::size_t i = 0; i < n; ++i) {
      va += (a[i] - ma) * (a[i] - ma);
      vb += (b[i] - mb) * (b[i] - mb);
      cab += (a[i] - ma) * (b[i] - mb);
    }
    return ssim_term(ma, mb, va / count, vb / count, cab / count);
  }
  const std::vector<double> map = ssim_map(a, b, width, height);
  double sum = 0.0;
  for (const double v : map) sum += v;
  return sum / static_cast<double>(map.size());
}

std::vector<double> ssim_map(const std::vector<double>& a, const std::vector<double>& b, int width,
                             int height) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (width < window || height < window || a.size() != n || b.size() != n)
    throw std::invalid_argument("ssim_map: expected two luminance images of " +
                                std::to_string(width) + "x" + std::to_string(height) +
                                " pixels, at least 11x11");
  std::vector<double> aa(n), bb(n), ab(n);
  for (std::size_t i = 0; i < n; ++i) {
    aa[i] = a[i] * a[i];
    bb[i] = b[i] * b[i];
    ab[i] = a[i] * b[i];
  }
  const std::vector<double> ma = filter_valid(a, width, height), mb = filter_valid(b, width, height);
  const std::vector<double> saa = filter_valid(aa, width, height),
                            sbb = filter_valid(bb, width, height),
                            sab = filter_valid(ab, width, height);
  std::vector<double> map(ma.size());
  for (std::size_t i = 0; i < ma.size(); ++i)
    map[i] = ssim_term(ma[i], mb[i], saa[i] - ma[i] * ma[i], sbb[i] - mb[i] * mb[i],
                       sab[i] - ma[i] * mb[i]);
  return map;
}

ImageDifference compare_images(const Image& a, const Image& b, int pixel_threshold) {
  return compare_images(a, b, pixel_threshold, {}, {});
}

ImageDifference compare_images(const Image& a, const Image& b, int pixel_threshold,
                               const std::vector<std::uint8_t>& alpha_a,
                               const std::vector<std::uint8_t>& alpha_b) {
  check_sizes(a, b);
  const std::size_t pixels = static_cast<std::size_t>(a.width()) * static_cast<std::size_t>(a.height());
  for (const auto* alpha : {&alpha_a, &alpha_b})
    if (!alpha->empty() && alpha->size() != pixels)
      throw std::invalid_argument("image comparison: an alpha channel of " +
                                  std::to_string(alpha->size()) + " values for " +
                                  std::to_string(pixels) + " pixels");
  ImageDifference d;
  d.width = a.width();
  d.height = a.height();
  d.pixel_threshold = pixel_threshold;
  d.has_alpha = !alpha_a.empty() || !alpha_b.empty();
  const int channels = d.has_alpha ? 4 : 3;
  // Channel c of pixel p; a missing alpha channel is opaque.
  const auto value = [&](const Image& image, const std::vector<std::uint8_t>& alpha,
                         std::size_t p, int c) -> int {
    if (c < 3) return image.data()[3 * p + static_cast<std::size_t>(c)];
    return alpha.empty() ? 255 : alpha[p];
  };
  std::array<double, 4> sum_abs{}, sum_sq{};
  long over = 0;
  const double count = static_cast<double>(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < channels; ++c) {
      const int e = std::abs(value(a, alpha_a, p, c) - value(b, alpha_b, p, c));
      sum_abs[static_cast<std::size_t>(c)] += e;
      sum_sq[static_cast<std::size_t>(c)] += double(e) * e;
      auto& ch = d.channels[static_cast<std::size_t>(c)];
      ch.max_abs = std::max(ch.max_abs, e);
      worst = std::max(worst, e);
    }
    over += worst > pixel_threshold;
  }
  double total_abs = 0.0, total_sq = 0.0;
  for (int c = 0; c < channels; ++c) {
    auto& ch = d.channels[static_cast<std::size_t>(c)];
    ch.mean_abs = sum_abs[static_cast<std::size_t>(c)] / count;
    ch.rms = std::sqrt(sum_sq[static_cast<std::size_t>(c)] / count);
    d.max_abs = std::max(d.max_abs, ch.max_abs);
    total_abs += sum_abs[static_cast<std::size_t>(c)];
    total_sq += sum_sq[static_cast<std::size_t>(c)];
  }
  d.mean_abs = total_abs / (channels * count);
  const double mse = total_sq / (channels * count);
  d.rms = std::sqrt(mse);
  d.psnr_db = mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse)
                        : std::numeric_limits<double>::infinity();
  d.ssim = ssim(luminance(a), luminance(b), a.width(), a.height());
  d.fraction_over = static_cast<double>(over) / count;
  return d;
}

Image difference_heatmap(const Image& a, const Image& b, int pixel_threshold) {
  check_sizes(a, b);
  Image out(a.width(), a.height());
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb8 p = a.at(x, y), q = b.at(x, y);
      const int d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
      if (d <= pixel_threshold) {
        const auto grey = static_cast<std::uint8_t>(std::lround(0.25 * (0.299 * q.r + 0.587 * q.g + 0.114 * q.b)));
        out.set(x, y, {grey, grey, grey});
      } else {
        out.set(x, y, heat_ramp(std::sqrt(d / 255.0)));
      }
    }
  return out;
}

}  // namespace weft::render
