// The renderers' contract (render_settings.h): checking settings, and the names of its
// enumerations.

#include "render/render_settings.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::render {

namespace {

template <class E>
const char* name_of(const NamedChoices<E>& choices, E value) {
  for (const auto& [name, v] : choices) {
    if (v == value) return name.c_str();
  }
  return choices.front().first.c_str();  // unreachable for a valid enumerator
}

// "expected 'a', 'b' or 'c', got 'name'".
template <class E>
E value_of(const NamedChoices<E>& choices, const std::string& name, const std::string& where) {
  std::string expected;
  for (std::size_t k = 0; k < choices.size(); ++k) {
    if (choices[k].first == name) return choices[k].second;
    expected += (k == 0 ? "'" : k + 1 == choices.size() ? " or '" : ", '") + choices[k].first + "'";
  }
  throw std::invalid_argument(where + ": expected " + expected + ", got '" + name + "'");
}

}  // namespace

void validate(const RenderSettings& s, int max_size) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RenderSettings: " + what);
  };
  if (s.width <= 0 || s.height <= 0 || s.width > max_size || s.height > max_size) {
    fail("width×height must be within 1.." + std::to_string(max_size) + ", got " +
         std::to_string(s.width) + "x" + std::to_string(s.height));
  }
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
}

const NamedChoices<Shading>& shading_choices() {
  static const NamedChoices<Shading> choices{{"lit", Shading::lit},
                                             {"normals", Shading::normals}};
  return choices;
}

const NamedChoices<RendererKind>& renderer_choices() {
  static const NamedChoices<RendererKind> choices{{"raster", RendererKind::raster},
                                                  {"raytrace", RendererKind::raytrace}};
  return choices;
}

const NamedChoices<GlBackend>& gl_backend_choices() {
  static const NamedChoices<GlBackend> choices{
      {"auto", GlBackend::automatic}, {"osmesa", GlBackend::osmesa}, {"egl", GlBackend::egl}};
  return choices;
}

const char* renderer_name(RendererKind kind) {
  return name_of(renderer_choices(), kind);
}

const char* gl_backend_name(GlBackend backend) {
  return name_of(gl_backend_choices(), backend);
}

RendererKind renderer_from_name(const std::string& name, const std::string& where) {
  return value_of(renderer_choices(), name, where);
}

GlBackend gl_backend_from_name(const std::string& name, const std::string& where) {
  return value_of(gl_backend_choices(), name, where);
}

}  // namespace weft::render
