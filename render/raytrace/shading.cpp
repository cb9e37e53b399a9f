// The ray tracer's shading functions (see shading.h for the model and its units).

#include "render/raytrace/shading.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"

namespace weft::render::rt {

namespace {

float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Coverage (0..1) of lines every `spacing` metres (cf. raster_shaders.cpp's grid()).
float grid(float x_m, float y_m, float spacing, float pixel_m) {
  const float cells_per_pixel = std::max(pixel_m / spacing, 1e-6f);
  const float fade = 1.0f - smoothstep(0.12f, 0.3f, cells_per_pixel);
  if (fade <= 0.0f) return 0.0f;  // lines closer than a few pixels: not drawn
  const auto pixels_to_line = [&](float c) {
    const float coord = c / spacing + 0.5f;
    return std::abs(coord - std::floor(coord) - 0.5f) / cells_per_pixel;
  };
  const float line =
      1.0f - std::clamp(std::min(pixels_to_line(x_m), pixels_to_line(y_m)) - 0.5f, 0.0f, 1.0f);
  return line * fade;
}

}  // namespace

Eigen::Vector3f reflectance_from_color(const Eigen::Vector3f& color) {
  return color.unaryExpr(
      [](float c) { return std::pow(std::clamp(c, 0.0f, 1.0f), display_gamma); });
}

unsigned char encode_channel(float radiance) {
  const float clamped = std::clamp(radiance, 0.0f, 1.0f);  // NaN stays NaN: checked below
  if (!(clamped >= 0.0f)) return 0;
  return static_cast<unsigned char>(std::lround(255.0f * std::pow(clamped, 1.0f / display_gamma)));
}

float ground_grid_lines(float x_m, float y_m, float pixel_m) {
  return std::max(0.07f * grid(x_m, y_m, 0.1f, pixel_m), 0.16f * grid(x_m, y_m, 1.0f, pixel_m));
}

}  // namespace weft::render::rt
