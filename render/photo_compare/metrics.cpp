// Photo-vs-render metrics; see metrics.h.

#include "render/photo_compare/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/image_diff.h"

namespace weft::render {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

void check_same_size(const Mask& a, const Mask& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("silhouette sizes differ");
}

// 1-D squared distance transform of f (lower envelope of parabolas), in place.
void squared_distance_1d(std::vector<double>& f) {
  const int n = static_cast<int>(f.size());
  std::vector<double> d(f.size()), z(f.size() + 1);
  std::vector<int> v(f.size());
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[static_cast<std::size_t>(q)] == infinity) continue;
    while (k >= 0) {
      const int p = v[static_cast<std::size_t>(k)];
      const double s = ((f[static_cast<std::size_t>(q)] + q * q) - (f[static_cast<std::size_t>(p)] + p * p)) /
                       (2.0 * (q - p));
      if (s > z[static_cast<std::size_t>(k)]) break;
      --k;
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] =
        k == 0 ? -infinity
               : ((f[static_cast<std::size_t>(q)] + q * q) -
                  (f[static_cast<std::size_t>(v[static_cast<std::size_t>(k - 1)])] +
                   v[static_cast<std::size_t>(k - 1)] * v[static_cast<std::size_t>(k - 1)])) /
                     (2.0 * (q - v[static_cast<std::size_t>(k - 1)]));
    z[static_cast<std::size_t>(k + 1)] = infinity;
  }
  if (k < 0) return;  // no finite value: all stay +∞
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(j + 1)] < q) ++j;
    const int p = v[static_cast<std::size_t>(j)];
    d[static_cast<std::size_t>(q)] = (q - p) * (q - p) + f[static_cast<std::size_t>(p)];
  }
  f = d;
}

std::vector<double> gaussian_blur(const std::vector<double>& v, int w, int h, double sigma) {
  const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> taps(static_cast<std::size_t>(2 * r + 1));
  double sum = 0.0;
  for (int k = -r; k <= r; ++k) sum += taps[static_cast<std::size_t>(k + r)] = std::exp(-k * k / (2 * sigma * sigma));
  for (double& t : taps) t /= sum;
  std::vector<double> tmp(v.size()), out(v.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -r; k <= r; ++k)
        s += taps[static_cast<std::size_t>(k + r)] * v[static_cast<std::size_t>(y) * w + std::clamp(x + k, 0, w - 1)];
      tmp[static_cast<std::size_t>(y) * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -r; k <= r; ++k)
        s += taps[static_cast<std::size_t>(k + r)] * tmp[static_cast<std::size_t>(std::clamp(y + k, 0, h - 1)) * w + x];
      out[static_cast<std::size_t>(y) * w + x] = s;
    }
  return out;
}

}  // namespace

double silhouette_iou(const Mask& a, const Mask& b) {
  check_same_size(a, b);
  long both = 0, either = 0;
  for (std::size_t i = 0; i < a.in.size(); ++i) {
    both += a.in[i] && b.in[i];
    either += a.in[i] || b.in[i];
  }
  return either == 0 ? 0.0 : static_cast<double>(both) / static_cast<double>(either);
}

std::vector<double> distance_transform(const Mask& features) {
  const int w = features.width, h = features.height;
  std::vector<double> d(features.in.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = features.in[i] ? 0.0 : infinity;
  std::vector<double> line;
  for (int x = 0; x < w; ++x) {  // columns
    line.assign(static_cast<std::size_t>(h), 0.0);
    for (int y = 0; y < h; ++y) line[static_cast<std::size_t>(y)] = d[static_cast<std::size_t>(y) * w + x];
    squared_distance_1d(line);
    for (int y = 0; y < h; ++y) d[static_cast<std::size_t>(y) * w + x] = line[static_cast<std::size_t>(y)];
  }
  for (int y = 0; y < h; ++y) {  // rows
    line.assign(d.begin() + static_cast<std::ptrdiff_t>(y) * w, d.begin() + static_cast<std::ptrdiff_t>(y + 1) * w);
    squared_distance_1d(line);
    std::copy(line.begin(), line.end(), d.begin() + static_cast<std::ptrdiff_t>(y) * w);
  }
  for (double& v : d) v = std::sqrt(v);
  return d;
}

ChamferDistance chamfer_distance(const Mask& a, const Mask& b) {
  check_same_size(a, b);
  const Mask oa = outline(a), ob = outline(b);
  const auto mean_distance = [](const Mask& from, const std::vector<double>& to) {
    double sum = 0.0;
    long n = 0;
    for (std::size_t i = 0; i < from.in.size(); ++i)
      if (from.in[i]) {
        sum += to[i];
        ++n;
      }
    if (n == 0) throw std::invalid_argument("Chamfer distance: a silhouette is empty");
    return sum / static_cast<double>(n);
  };
  ChamferDistance c;
  c.a_to_b_px = mean_distance(oa, distance_transform(ob));
  c.b_to_a_px = mean_distance(ob, distance_transform(oa));
  c.symmetric_px = 0.5 * (c.a_to_b_px + c.b_to_a_px);
  c.percent_of_diagonal = 100.0 * c.symmetric_px / std::hypot(a.width, a.height);
  return c;
}

std::vector<std::int8_t> fold_labels(const std::vector<double>& luminance, int w, int h,
                                     double sigma_px, const Mask& region) {
  const std::vector<double> s = gaussian_blur(luminance, w, h, sigma_px);
  const auto at = [&](int x, int y) {
    return s[static_cast<std::size_t>(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)];
  };
  std::vector<double> lambda(s.size(), 0.0), magnitudes;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!region.at(x, y)) continue;
      const double ixx = at(x + 1, y) - 2 * at(x, y) + at(x - 1, y);
      const double iyy = at(x, y + 1) - 2 * at(x, y) + at(x, y - 1);
      const double ixy = 0.25 * (at(x + 1, y + 1) - at(x - 1, y + 1) - at(x + 1, y - 1) + at(x - 1, y - 1));
      const double mean = 0.5 * (ixx + iyy), root = std::hypot(0.5 * (ixx - iyy), ixy);
      const double l = std::abs(mean + root) >= std::abs(mean - root) ? mean + root : mean - root;
      lambda[static_cast<std::size_t>(y) * w + x] = l;
      magnitudes.push_back(std::abs(l));
    }
  std::vector<std::int8_t> labels(s.size(), 0);
  if (magnitudes.empty()) return labels;
  const auto mid = magnitudes.begin() + static_cast<std::ptrdiff_t>(magnitudes.size() / 2);
  std::nth_element(magnitudes.begin(), mid, magnitudes.end());
  const double threshold = std::max(*mid, 1e-3);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (region.in[i] && std::abs(lambda[i]) >= threshold) labels[i] = lambda[i] < 0 ? 1 : -1;
  return labels;
}

FoldAgreement fold_agreement(const std::vector<double>& photo, const std::vector<double>& render,
                             int w, int h, const Mask& overlap, double sigma_px) {
  FoldAgreement f;
  f.sigma_px = sigma_px > 0 ? sigma_px : std::max(1.5, 0.01 * std::hypot(w, h));
  // The overlap less a band of ceil(3σ) pixels along its edge and the image's.
  const int band = static_cast<int>(std::ceil(3.0 * f.sigma_px));
  Mask outside(w, h);
  for (std::size_t i = 0; i < outside.in.size(); ++i) outside.in[i] = overlap.in[i] ? 0 : 1;
  const std::vector<double> depth = distance_transform(outside);
  Mask region(w, h);
  for (int y = band; y < h - band; ++y)
    for (int x = band; x < w - band; ++x)
      if (depth[static_cast<std::size_t>(y) * w + x] > band) {
        region.set(x, y, true);
        ++f.compared_px;
      }
  f.photo_labels = fold_labels(photo, w, h, f.sigma_px, region);
  f.render_labels = fold_labels(render, w, h, f.sigma_px, region);
  long photo_n = 0, render_n = 0, agree = 0;
  for (std::size_t i = 0; i < region.in.size(); ++i) {
    photo_n += f.photo_labels[i] != 0;
    render_n += f.render_labels[i] != 0;
    agree += f.photo_labels[i] != 0 && f.photo_labels[i] == f.render_labels[i];
  }
  if (photo_n == 0 && render_n == 0) {
    f.precision = f.recall = f.f_score = 1.0;
    return f;
  }
  f.precision = render_n ? static_cast<double>(agree) / static_cast<double>(render_n) : 0.0;
  f.recall = photo_n ? static_cast<double>(agree) / static_cast<double>(photo_n) : 0.0;
  f.f_score = f.precision + f.recall > 0 ? 2 * f.precision * f.recall / (f.precision + f.recall) : 0.0;
  return f;
}

double overlap_ssim(const std::vector<double>& photo, const std::vector<double>& render, int w,
                    int h, const Mask& overlap) {
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (overlap.at(x, y)) {
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x);
        y1 = std::max(y1, y);
      }
  if (x1 < 0) throw std::invalid_argument("SSIM inside the overlap: the silhouettes do not overlap");
  const int bw = x1 - x0 + 1, bh = y1 - y0 + 1;
  std::vector<double> a(static_cast<std::size_t>(bw) * bh), b(a.size());
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x) {
      const std::size_t i = static_cast<std::size_t>(y + y0) * w + (x + x0);
      const std::size_t o = static_cast<std::size_t>(y) * bw + x;
      a[o] = photo[i];
      b[o] = overlap.in[i] ? render[i] : photo[i];
    }
  return ssim(a, b, bw, bh);
}

}  // namespace weft::render
