#pragma once
// The ray tracer's denoiser: an edge-aware à-trous wavelet filter (Dammertz
// et al. 2010, "Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination
// Filtering") guided by each pixel's first-hit normal, albedo and depth, its colour edges
// stopped by the pixel's own estimated noise (the luminance weight of Schied et al. 2017,
// "Spatiotemporal Variance-Guided Filtering", SVGF, spatial part only). The illumination is
// filtered, not the colour: radiance is divided by the albedo first and multiplied back after,
// so texture and colour edges stay sharp.
//
// Deterministic: each output pixel is a fixed function of its neighbourhood, computed in a
// fixed order, so the result is the same bits for any number of threads.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace weft::base {
class ThreadPool;
}

namespace weft::render {

// Per pixel, row by row from the top (width × height each), from the pixel's camera samples.
struct DenoiseInput {
  int width = 0, height = 0;
  std::vector<Eigen::Vector3f> radiance;  // mean linear radiance
  // Variance of the mean of the samples' illumination luminance (radiance luminance / albedo
  // luminance): the noise the luminance weight allows for. 0: noise-free, never averaged.
  std::vector<float> variance;
  std::vector<Eigen::Vector3f> normal;  // mean first-hit shading normal (not unit at edges)
  std::vector<Eigen::Vector3f> albedo;  // mean first-hit reflectance
  std::vector<float> depth_m;           // mean first-hit distance
  // Fraction of the samples that hit a surface: only pixels at 1 are filtered and taken as
  // neighbours (the background and the antialiased silhouette are kept as they are).
  std::vector<float> coverage;
  // Per pixel (or empty: none), non-zero where the samples' first hits were on different
  // surfaces or colours (PixelGuide::mixed): such a pixel is kept as it is and is no neighbour,
  // as a partly covered one — its mean albedo and normal describe neither side, and filtering
  // its illumination with its neighbours' darkens or lightens the edge.
  std::vector<std::uint8_t> mixed;
};

struct DenoiseSettings {
  int iterations = 5;             // kernel steps 1, 2, 4, 8, 16 pixels: a 61-pixel footprint
  float sigma_luminance = 4.0f;   // luminance differences allowed, in standard deviations
  float normal_power = 128.0f;    // weight (n_p · n_q)^power
  float sigma_depth = 1.0f;       // depth differences allowed, in units of the local gradient
  float sigma_albedo = 0.1f;      // reflectance differences allowed
};

// The denoised radiance (width × height). Bad input (sizes that do not match) is a bug here:
// checked with WEFT_CHECK. `pool` may be null (one thread). `variance`, when given, receives
// each pixel's variance of its illumination luminance after filtering (the input's where the
// pixel is not filtered): what adaptive sampling asks of it.
std::vector<Eigen::Vector3f> denoise(const DenoiseInput& input, const DenoiseSettings& settings,
                                     base::ThreadPool* pool, std::vector<float>* variance = nullptr);
// Whether pixel p is filtered (and a neighbour): all its samples hit, none mixed.
inline bool denoised_pixel(const DenoiseInput& in, std::size_t p) {
  return in.coverage[p] >= 1.0f && (in.mixed.empty() || in.mixed[p] == 0);
}

}  // namespace weft::render
