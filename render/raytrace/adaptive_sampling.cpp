// Adaptive sampling's display error (see adaptive_sampling.h).

#include "render/raytrace/adaptive_sampling.h"

#include "render/raytrace/shading.h"

namespace weft::render::rt {

float display_value(float radiance) {
  return 255.0f * std::pow(std::clamp(radiance, 0.0f, 1.0f), 1.0f / display_gamma);
}

}  // namespace weft::render::rt
