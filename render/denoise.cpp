// The à-trous denoiser (see denoise.h).

#include "render/denoise.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "base/check.h"
#include "base/thread_pool.h"
#include "render/environment.h"

namespace weft::render {

namespace {

float luminance_of(const Eigen::Vector3f& c) { return static_cast<float>(luminance(c)); }

// The B3-spline taps of each à-trous level: 1/16, 1/4, 3/8, 1/4, 1/16.
constexpr float taps[5] = {1.0f / 16.0f, 0.25f, 0.375f, 0.25f, 1.0f / 16.0f};

// Runs row(y) for every row, over the pool's threads when there is one.
void for_rows(int height, base::ThreadPool* pool, const std::function<void(int)>& row) {
  if (pool)
    pool->run(static_cast<std::size_t>(height), [&](std::size_t y) { row(static_cast<int>(y)); });
  else
    for (int y = 0; y < height; ++y) row(y);
}

// The image being filtered: illumination and its variance per pixel, and the fixed guides.
struct Level {
  std::vector<Eigen::Vector3f> illumination;
  std::vector<float> variance;
};

class AtrousFilter {
 public:
  AtrousFilter(const DenoiseInput& in, const DenoiseSettings& s) : m_in(in), m_s(s) {
    const std::size_t n = in.radiance.size();
    m_filtered.assign(n, false);
    m_normal.resize(n);
    m_depth_gradient.resize(n, 0.0f);
    for (int y = 0; y < in.height; ++y) {
      for (int x = 0; x < in.width; ++x) {
        const std::size_t p = index(x, y);
        m_filtered[p] = denoised_pixel(in, p);
        const float length = in.normal[p].norm();
        m_normal[p] = length > 0.0f ? Eigen::Vector3f(in.normal[p] / length) : Eigen::Vector3f::Zero();
        m_depth_gradient[p] = depth_gradient(x, y);
      }
    }
  }

  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(m_in.width) + static_cast<std::size_t>(x);
  }
  bool filtered(std::size_t p) const { return m_filtered[p]; }

  // One à-trous level with holes `step` pixels apart: out's row y from in.
  void filter_row(const Level& in, Level& out, int y, int step) const {
    for (int x = 0; x < m_in.width; ++x) {
      const std::size_t p = index(x, y);
      const float local = m_filtered[p] ? local_variance(in, x, y) : 0.0f;
      if (!(local > 0.0f)) {  // not filtered, or its samples and its neighbours' agree
        out.illumination[p] = in.illumination[p];
        out.variance[p] = in.variance[p];
        continue;
      }
      const float lp = luminance_of(in.illumination[p]);
      const float spread = m_s.sigma_luminance * std::sqrt(local);
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      float weights = 0.0f, variance = 0.0f;
      for (int j = -2; j <= 2; ++j) {
        const int qy = y + j * step;
        if (qy < 0 || qy >= m_in.height) continue;
        for (int i = -2; i <= 2; ++i) {
          const int qx = x + i * step;
          if (qx < 0 || qx >= m_in.width) continue;
          const std::size_t q = index(qx, qy);
          if (!m_filtered[q]) continue;
          const float w = taps[i + 2] * taps[j + 2] *
                          edge_weight(p, q, lp, luminance_of(in.illumination[q]), spread,
                                      step * (std::abs(i) + std::abs(j)));
          sum += w * in.illumination[q];
          weights += w;
          variance += w * w * in.variance[q];
        }
      }
      if (!(weights > 0.0f)) {  // no usable normal, even its own: kept
        out.illumination[p] = in.illumination[p];
        out.variance[p] = in.variance[p];
        continue;
      }
      out.illumination[p] = sum / weights;
      out.variance[p] = variance / (weights * weights);
    }
  }

 private:
  // The product of the guides' edge-stopping weights between pixels p and q, `distance`
  // pixels apart (L1), and their luminance weight.
  float edge_weight(std::size_t p, std::size_t q, float lp, float lq, float spread,
                    int distance) const {
    const float normal = std::pow(std::max(0.0f, m_normal[p].dot(m_normal[q])), m_s.normal_power);
    const float depth_scale = m_s.sigma_depth * m_depth_gradient[p] * static_cast<float>(distance) + 1e-4f;
    const float depth = std::abs(m_in.depth_m[p] - m_in.depth_m[q]) / depth_scale;
    const float albedo = (m_in.albedo[p] - m_in.albedo[q]).squaredNorm() / (m_s.sigma_albedo * m_s.sigma_albedo);
    const float colour = std::abs(lp - lq) / spread;
    return normal * std::exp(-depth - albedo - colour);
  }

  // Largest one-pixel change of depth about (x, y) among its covered neighbours, m per pixel.
  float depth_gradient(int x, int y) const {
    const float d = m_in.depth_m[index(x, y)];
    float g = 0.0f;
    const int dx[] = {-1, 1, 0, 0}, dy[] = {0, 0, -1, 1};
    for (int k = 0; k < 4; ++k) {
      const int qx = x + dx[k], qy = y + dy[k];
      if (qx < 0 || qy < 0 || qx >= m_in.width || qy >= m_in.height) continue;
      const std::size_t q = index(qx, qy);
      if (m_in.coverage[q] >= 1.0f) g = std::max(g, std::abs(m_in.depth_m[q] - d));
    }
    return g;
  }

  // The variance about (x, y), blurred over its 3 × 3 covered neighbours (SVGF's prefilter):
  // a single pixel's estimate from a few samples is itself noisy.
  float local_variance(const Level& in, int x, int y) const {
    float sum = 0.0f, weights = 0.0f;
    for (int j = -1; j <= 1; ++j) {
      for (int i = -1; i <= 1; ++i) {
        const int qx = x + i, qy = y + j;
        if (qx < 0 || qy < 0 || qx >= m_in.width || qy >= m_in.height) continue;
        const std::size_t q = index(qx, qy);
        if (!m_filtered[q]) continue;
        const float w = (i == 0 ? 2.0f : 1.0f) * (j == 0 ? 2.0f : 1.0f);
        sum += w * in.variance[q];
        weights += w;
      }
    }
    return sum / weights;
  }

  const DenoiseInput& m_in;
  const DenoiseSettings& m_s;
  std::vector<bool> m_filtered;
  std::vector<Eigen::Vector3f> m_normal;  // unit, or zero
  std::vector<float> m_depth_gradient;
};

}  // namespace

std::vector<Eigen::Vector3f> denoise(const DenoiseInput& in, const DenoiseSettings& s,
                                     base::ThreadPool* pool, std::vector<float>* variance) {
  const std::size_t n = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height);
  WEFT_CHECK(in.radiance.size() == n && in.variance.size() == n && in.normal.size() == n &&
                 in.albedo.size() == n && in.depth_m.size() == n && in.coverage.size() == n &&
                 (in.mixed.empty() || in.mixed.size() == n),
             "denoise: every buffer must have width × height pixels");
  // Demodulate: the illumination is radiance / albedo (per channel, where the albedo is not 0).
  const auto safe = [](const Eigen::Vector3f& a) { return a.cwiseMax(Eigen::Vector3f::Constant(1e-3f)); };
  Level level{std::vector<Eigen::Vector3f>(n), in.variance};
  for (std::size_t p = 0; p < n; ++p) level.illumination[p] = in.radiance[p].cwiseQuotient(safe(in.albedo[p]));
  const AtrousFilter filter(in, s);
  Level next{std::vector<Eigen::Vector3f>(n), std::vector<float>(n)};
  for (int k = 0; k < s.iterations; ++k) {
    const int step = 1 << k;
    for_rows(in.height, pool, [&](int y) { filter.filter_row(level, next, y, step); });
    std::swap(level, next);
  }
  if (variance) *variance = level.variance;
  std::vector<Eigen::Vector3f> out(n);
  for (std::size_t p = 0; p < n; ++p)
    out[p] = filter.filtered(p) ? Eigen::Vector3f(level.illumination[p].cwiseProduct(safe(in.albedo[p])))
                                : in.radiance[p];
  return out;
}

}  // namespace weft::render
