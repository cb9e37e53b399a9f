// Silhouette segmentation and mask operations; see silhouette.h.

#include "render/photo_compare/silhouette.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weft::render {
namespace {

struct Ycc {
  double y, cb, cr;
};

Ycc to_ycc(Rgb8 p) {  // BT.601, 0…255 scale, chroma centred on 0
  const double r = p.r, g = p.g, b = p.b;
  return {0.299 * r + 0.587 * g + 0.114 * b, -0.168736 * r - 0.331264 * g + 0.5 * b,
          0.5 * r - 0.418688 * g - 0.081312 * b};
}

std::uint8_t median(std::vector<std::uint8_t> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

Rgb8 border_median(const Image& image) {
  const int w = image.width(), h = image.height();
  const int band = std::max(1, static_cast<int>(std::lround(0.01 * std::min(w, h))));
  std::vector<std::uint8_t> r, g, b;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x >= band && y >= band && x < w - band && y < h - band) continue;
      const Rgb8 p = image.at(x, y);
      r.push_back(p.r);
      g.push_back(p.g);
      b.push_back(p.b);
    }
  return {median(r), median(g), median(b)};
}

// Otsu's threshold on values ≥ 0: maximises the between-class variance of a 256-bin histogram.
double otsu_threshold(const std::vector<double>& values, double max_value) {
  constexpr int bins = 256;
  std::vector<double> hist(bins, 0.0);
  for (double v : values)
    ++hist[static_cast<std::size_t>(std::min(bins - 1, static_cast<int>(v / max_value * bins)))];
  double total = 0.0, sum_all = 0.0;
  for (int i = 0; i < bins; ++i) {
    total += hist[static_cast<std::size_t>(i)];
    sum_all += i * hist[static_cast<std::size_t>(i)];
  }
  double w0 = 0.0, sum0 = 0.0, best = -1.0;
  int best_bin = 0;
  for (int i = 0; i < bins - 1; ++i) {
    w0 += hist[static_cast<std::size_t>(i)];
    sum0 += i * hist[static_cast<std::size_t>(i)];
    const double w1 = total - w0;
    if (w0 <= 0.0 || w1 <= 0.0) continue;
    const double m0 = sum0 / w0, m1 = (sum_all - sum0) / w1;
    const double between = w0 * w1 * (m0 - m1) * (m0 - m1);
    if (between > best) {
      best = between;
      best_bin = i;
    }
  }
  return (best_bin + 1) * max_value / bins;  // upper edge of the background class
}

// Labels the 4-connected components of the pixels equal to `value`; returns the label of each
// pixel (−1 for the other pixels) and the component sizes.
std::vector<int> components(const Mask& m, bool value, std::vector<int>& sizes) {
  std::vector<int> label(m.in.size(), -1);
  std::vector<int> stack;
  for (int start = 0; start < static_cast<int>(m.in.size()); ++start) {
    if ((m.in[static_cast<std::size_t>(start)] != 0) != value || label[static_cast<std::size_t>(start)] >= 0)
      continue;
    const int id = static_cast<int>(sizes.size());
    sizes.push_back(0);
    stack.push_back(start);
    label[static_cast<std::size_t>(start)] = id;
    while (!stack.empty()) {
      const int p = stack.back();
      stack.pop_back();
      ++sizes.back();
      const int x = p % m.width, y = p / m.width;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= m.width || ny[k] >= m.height) continue;
        const int q = ny[k] * m.width + nx[k];
        if ((m.in[static_cast<std::size_t>(q)] != 0) != value || label[static_cast<std::size_t>(q)] >= 0)
          continue;
        label[static_cast<std::size_t>(q)] = id;
        stack.push_back(q);
      }
    }
  }
  return label;
}

}  // namespace

Segmentation segment_cloth(const Image& image, const SegmentationSettings& settings) {
  if (image.width() <= 0 || image.height() <= 0)
    throw std::invalid_argument("segmentation: the image is empty");
  Segmentation s;
  s.background = border_median(image);
  const Ycc bg = to_ycc(s.background);
  const int w = image.width(), h = image.height();
  std::vector<double> d(static_cast<std::size_t>(w) * h);
  double max_d = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Ycc c = to_ycc(image.at(x, y));
      const double dy = settings.luma_weight * (c.y - bg.y), dcb = c.cb - bg.cb, dcr = c.cr - bg.cr;
      const double v = std::sqrt(dcb * dcb + dcr * dcr + dy * dy);
      d[static_cast<std::size_t>(y) * w + x] = v;
      max_d = std::max(max_d, v);
    }
  // Below one grey level of difference nothing stands out of the background.
  if (max_d < 1.0)
    throw std::invalid_argument("empty silhouette: nothing differs from the background colour");
  s.threshold = otsu_threshold(d, max_d);
  Mask raw(w, h);
  for (std::size_t i = 0; i < d.size(); ++i) raw.in[i] = d[i] > s.threshold ? 1 : 0;
  s.mask = fill_holes(largest_component(raw));
  return s;
}

Mask mask_from_image(const Image& image) {
  Mask m(image.width(), image.height());
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const Rgb8 p = image.at(x, y);
      m.set(x, y, 0.299 * p.r + 0.587 * p.g + 0.114 * p.b >= 128.0);
    }
  return m;
}

Mask largest_component(const Mask& mask) {
  std::vector<int> sizes;
  const std::vector<int> label = components(mask, true, sizes);
  Mask out(mask.width, mask.height);
  if (sizes.empty()) return out;
  const int best = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  for (std::size_t i = 0; i < label.size(); ++i) out.in[i] = label[i] == best ? 1 : 0;
  return out;
}

Mask fill_holes(const Mask& mask) {
  std::vector<int> sizes;
  const std::vector<int> label = components(mask, false, sizes);
  std::vector<bool> touches_border(sizes.size(), false);
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (x != 0 && y != 0 && x != mask.width - 1 && y != mask.height - 1) continue;
      const int l = label[static_cast<std::size_t>(y) * mask.width + x];
      if (l >= 0) touches_border[static_cast<std::size_t>(l)] = true;
    }
  Mask out = mask;
  for (std::size_t i = 0; i < label.size(); ++i)
    if (label[i] >= 0 && !touches_border[static_cast<std::size_t>(label[i])]) out.in[i] = 1;
  return out;
}

Mask outline(const Mask& mask) {
  Mask out(mask.width, mask.height);
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y) && (!mask.at_or_out(x - 1, y) || !mask.at_or_out(x + 1, y) ||
                            !mask.at_or_out(x, y - 1) || !mask.at_or_out(x, y + 1)))
        out.set(x, y, true);
  return out;
}

SilhouetteMoments moments(const Mask& mask) {
  SilhouetteMoments m;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y)) {
        m.area_px += 1.0;
        m.cx += x;
        m.cy += y;
      }
  if (m.area_px > 0) {
    m.cx /= m.area_px;
    m.cy /= m.area_px;
  }
  return m;
}

namespace {

// How many mask pixels each pixel's (2 radius + 1)² window, clipped to the image, holds; by a
// summed-area table.
std::vector<long> window_counts(const Mask& mask, int radius) {
  const int w = mask.width, h = mask.height;
  std::vector<long> sat(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0);
  const auto at = [&](int x, int y) -> long& { return sat[static_cast<std::size_t>(y) * (w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      at(x + 1, y + 1) = (mask.at(x, y) ? 1 : 0) + at(x, y + 1) + at(x + 1, y) - at(x, y);
  std::vector<long> counts(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(w, x + radius + 1);
      const int y0 = std::max(0, y - radius), y1 = std::min(h, y + radius + 1);
      counts[static_cast<std::size_t>(y) * w + x] = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
    }
  return counts;
}

}  // namespace

Mask eroded_mask(const Mask& mask, int radius) {
  const std::vector<long> counts = window_counts(mask, radius);
  const long full = static_cast<long>(2 * radius + 1) * (2 * radius + 1);
  Mask out(mask.width, mask.height);
  for (std::size_t i = 0; i < counts.size(); ++i) out.in[i] = counts[i] == full;
  return out;
}

Mask dilated_mask(const Mask& mask, int radius) {
  const std::vector<long> counts = window_counts(mask, radius);
  Mask out(mask.width, mask.height);
  for (std::size_t i = 0; i < counts.size(); ++i) out.in[i] = counts[i] > 0;
  return out;
}

}  // namespace weft::render
