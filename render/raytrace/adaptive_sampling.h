#pragma once
// Adaptive sampling, in two passes over the image (render/raytrace/ray_tracer.cpp):
//   1. every pixel takes `round_samples` camera samples;
//   2. the denoiser (render/denoise.h) filters them and says how noisy each pixel's filtered
//      illumination still is; a pixel it does not filter (silhouettes, edges, background) keeps
//      the standard error of its own samples' mean. That standard error of the pixel's luminance
//      is carried into display space — the 8-bit value round(255 · clamp(L, 0, 1)^(1/2.2)) the ray
//      tracer writes (shading.h) — as half the spread of the displayed values at mean ± error;
//      a pixel whose error is above max_error takes n · (error / max_error)² samples in all
//      (the error of a mean falls as 1/√n), at most samples_per_pixel, continuing its own
//      sample sequence; then the image is denoised again.
// The noise that remains after denoising decides, not the raw samples' spread: a flat, lit,
// filtered surface stops early however noisy its samples, while the pixels the filter cannot
// help (a fold's edge, a silhouette, a penumbra it keeps) take more. Every decision is a fixed
// function of the first pass, which is itself thread-count independent, so the image is too.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace weft::render::rt {

// Display value (0..255, unrounded) of linear radiance L: 255 · clamp(L, 0, 1)^(1/2.2).
float display_value(float radiance);

// Display levels of a linear luminance mean m with standard error e: half the spread of the
// displayed values of m − e and m + e (bounded where the display curve is steep or clamps).
inline float display_error(float mean, float standard_error) {
  return 0.5f * (display_value(mean + standard_error) - display_value(mean - standard_error));
}

// Running sums of one pixel's samples: radiance per channel and the luminance's squares.
class PixelSamples {
 public:
  void add(const Eigen::Vector3f& radiance, double luminance) {
    m_sum += radiance.cast<double>();
    m_luminance_sum += luminance;
    m_luminance_squares += luminance * luminance;
    ++m_count;
  }
  int count() const { return m_count; }
  Eigen::Vector3f mean() const {
    return m_count > 0 ? Eigen::Vector3f((m_sum / m_count).cast<float>()) : Eigen::Vector3f::Zero();
  }
  float luminance_mean() const {
    return m_count > 0 ? static_cast<float>(m_luminance_sum / m_count) : 0.0f;
  }
  // The standard error of the luminance's mean (0 below two samples): the samples' unbiased
  // standard deviation over √n.
  float luminance_standard_error() const {
    if (m_count < 2) return 0.0f;
    const double n = m_count;
    const double variance =
        std::max(0.0, (m_luminance_squares - m_luminance_sum * m_luminance_sum / n) / (n - 1.0));
    return static_cast<float>(std::sqrt(variance / n));
  }

 private:
  Eigen::Vector3d m_sum = Eigen::Vector3d::Zero();
  double m_luminance_sum = 0.0, m_luminance_squares = 0.0;
  int m_count = 0;
};

struct AdaptiveSampling {
  int round_samples = 16;  // samples of the first pass (at most samples_per_pixel)
  // Display levels (0..255) of standard error a pixel may keep after denoising; 0: off (every
  // pixel takes samples_per_pixel in one pass).
  float max_error = 0.0f;
};

// Samples a pixel takes in all, having shown `error` display levels of standard error with
// `taken` samples: taken · (error / max_error)², rounded up, within [taken, most].
inline int samples_needed(int taken, float error, float max_error, int most) {
  if (!(error > max_error) || taken >= most) return std::min(taken, most);
  const double ratio = static_cast<double>(error) / max_error;
  const double needed = std::ceil(taken * ratio * ratio);
  return needed >= most ? most : std::max(taken, static_cast<int>(needed));
}

}  // namespace weft::render::rt
