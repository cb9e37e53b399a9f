// The renderers' contract (render_settings.h): checking settings, and the names of its
// enumerations.

#include "render/render_settings.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::render {

void validate(const RenderSettings& s, int max_size) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RenderSettings: " + what);
  };
  if (s.width <= 0 || s.height <= 0 || s.width > max_size || s.height > max_size) {
    fail("width×height must be within 1.." + std::to_string(max_size) + ", got " +
         std::to_string(s.width) + "x" + std::to_string(s.height));
  }
  if (!(s.strain_full_scale > 0.0) || !std::isfinite(s.strain_full_scale))
    fail("strain_full_scale must be finite and > 0");
  if (s.msaa_samples < 0) fail("msaa_samples must be >= 0, got " + std::to_string(s.msaa_samples));
  if (!s.light_direction.allFinite() || !(s.light_direction.norm() > 0.0)) {
    fail("light_direction must be a finite non-zero vector");
  }
  if (!(s.light_intensity >= 0.0) || !std::isfinite(s.light_intensity)) {
    fail("light_intensity must be finite and >= 0");
  }
  if (!(s.ambient >= 0.0) || !std::isfinite(s.ambient)) fail("ambient must be finite and >= 0");
  if (s.ground && (!(s.ground_half_size_m > 0.0) || !std::isfinite(s.ground_half_size_m) ||
                   !std::isfinite(s.ground_z_m))) {
    fail("ground needs a finite ground_z_m and ground_half_size_m > 0");
  }
  validate(s.environment);
}

std::vector<std::string> renderer_choices() {
  return base::enum_name_list(renderer_names);
}

const char* renderer_name(RendererKind kind) {
  return base::enum_name(renderer_names, kind);
}

const char* gl_backend_name(GlBackend backend) {
  return base::enum_name(gl_backend_names, backend);
}

RendererKind renderer_from_name(const std::string& name, const std::string& where) {
  return base::parse_enum(renderer_names, name, where);
}

GlBackend gl_backend_from_name(const std::string& name, const std::string& where) {
  return base::parse_enum(gl_backend_names, name, where);
}

}  // namespace weft::render
