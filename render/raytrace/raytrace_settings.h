#pragma once
// Settings of the Embree ray tracer (render/raytrace/ray_tracer.h) that the rasterizer has no
// use for: samples, bounces, ambient occlusion, soft shadows and threads (the cloth's sheen is both
// renderers', in ClothSurface). Header
// only and free of Embree, so that scene files can hold them whether or not the ray tracer is
// built (CMake option WEFT_WITH_EMBREE_RT).

#include <cstdint>

namespace weft::render {

struct RayTraceSettings {
  // Camera samples per pixel: with adaptive sampling the most a pixel takes; 1: one ray through
  // the pixel centre.
  int samples_per_pixel = 256;
  // Adaptive sampling (render/raytrace/adaptive_sampling.h): every pixel takes adaptive_round
  // samples, then those whose standard error after denoising is above adaptive_error display
  // levels (8-bit, of the luminance) take as many more as that error asks, up to
  // samples_per_pixel; 0: every pixel takes samples_per_pixel.
  double adaptive_error = 0.5;
  int adaptive_round = 16;
  // 0: direct sun light + ambient occlusion (AO); N > 0: path tracing with N diffuse bounces
  // (the last vertex still takes the sky through AO).
  int bounces = 0;
  int ao_samples = 1;          // AO rays per camera sample (0: the sky is never occluded)
  double ao_distance_m = 1.0;  // occluders farther than this do not darken
  // Angular radius of the sun's disc: shadow rays are spread over this cone (0: hard shadows).
  double sun_angular_radius_deg = 2.0;
  // Edge-aware à-trous denoising guided by normal, albedo and depth (render/denoise.h); off:
  // the plain mean of the samples.
  bool denoise = true;
  int threads = 0;         // render threads; 0: all hardware threads. Never changes a bit.
  std::uint32_t seed = 0;  // mixed into every pixel's random generator
};

}  // namespace weft::render
