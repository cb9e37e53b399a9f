#pragma once
// The renderers' contract: what a frame is drawn with (RenderSettings), the opaque objects
// drawn beside the cloth (RenderObject), which renderer draws (RendererKind) and which GL
// context the rasterizer gets (GlBackend), with the names scene files use for them. Free of
// OpenGL and Embree: the rasterizer (raster.h) and the ray tracer (raytrace/ray_tracer.h) both
// draw from it, and app/ reads scene files into it and chooses a renderer through renderer.h.
// The ray tracer's own settings (RenderSettings::raytrace) are in raytrace/raytrace_settings.h,
// as free of Embree as this header.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/enum_names.h"
#include "render/camera.h"
#include "render/cloth_surface.h"
#include "render/environment.h"
#include "render/raytrace/raytrace_settings.h"
#include "render/render_mesh.h"

namespace weft::render {

// normals: |n| as colour (seed 003's debug view); strain: the cloth lit in the false colour of
// RenderMesh::strain (render/strain_colour.h) on both sides, with a legend.
enum class Shading { lit, normals, strain };

// Which renderer draws the frames (render/renderer.h): the OpenGL rasterizer or the Embree
// ray tracer.
enum class RendererKind { raster, raytrace };

// Which OpenGL context the rasterizer gets (render/gl_context.h). automatic: OSMesa when it was
// built and starts, else EGL.
enum class GlBackend { automatic, osmesa, egl };

struct RenderSettings {
  int width = 640, height = 480;
  Camera camera;
  Eigen::Vector3d light_direction{0.4, -0.6, 1.0};  // towards the key light, need not be unit
  double light_intensity = 0.85;                    // key light, diffuse
  double ambient = 0.25;
  Eigen::Vector3f front_color{0.80f, 0.25f, 0.20f};  // as displayed, 0..1
  // None (the default): the cloth is one fabric, its back the same as its front (colour,
  // texture and sheen). A colour: the back is plain that colour, e.g. to tell the sides apart.
  std::optional<Eigen::Vector3f> back_color;
  Eigen::Vector3f background{0.92f, 0.93f, 0.95f};
  bool ground = true;
  double ground_z_m = 0.0;
  double ground_half_size_m = 5.0;
  Eigen::Vector3f ground_color{0.60f, 0.60f, 0.58f};
  // Colour app/ gives obstacles (RenderObject::color); the renderer itself does not read it.
  Eigen::Vector3f obstacle_color{0.70f, 0.74f, 0.80f};
  // What holds the cloth — clips on pins, rods on held edges, a flag's pole, stands under
  // floating obstacles — drawn by app/ as RenderObjects of this colour (app/run/support_meshes.h).
  bool supports = true;
  Eigen::Vector3f support_color{0.22f, 0.22f, 0.24f};
  Shading shading = Shading::lit;
  double strain_full_scale = 0.05;  // Shading::strain: the strain of the map's ends (±5 %)
  int msaa_samples = 4;
  RendererKind renderer = RendererKind::raster;
  // The rasterizer's GL context. render/ reads no environment: app/ applies WEFT_GL here.
  GlBackend gl = GlBackend::automatic;
  RayTraceSettings raytrace;  // read by the ray tracer only
  // Subdivision, thickness shell and texture of the cloth (render/cloth_surface.h): the mesh
  // aids are applied by the Renderer interface (renderer.h), the texture by each renderer.
  ClothSurface cloth_surface;
  // Image-based lighting (render/environment.h): a map replaces the ambient sky in both
  // renderers (the ray tracer samples it, the rasterizer takes its spherical-harmonic
  // irradiance) and, with environment.background, the background colour. The key light stays.
  Environment environment;
};

// The colour of the cloth's back side where no texture covers it: back_color, else front_color.
inline Eigen::Vector3f back_side_color(const RenderSettings& settings) {
  return settings.back_color.value_or(settings.front_color);
}
// Whether the texture (cloth_surface.texture) covers the back side too: unless back_color is set.
inline bool texture_on_back(const RenderSettings& settings) { return !settings.back_color; }

// Bad input: throws std::invalid_argument naming the field ("RenderSettings: ...") unless the
// settings can be drawn; max_size is the largest width or height the renderer supports.
void validate(const RenderSettings& settings, int max_size);

// An opaque object drawn with the cloth (e.g. an obstacle): lit like the cloth's front side,
// in one colour on both sides, depth-tested against the cloth and the other objects, and
// casting a shadow on the ground as the cloth does.
struct RenderObject {
  RenderMesh mesh;                             // normals computed when missing
  Eigen::Vector3f color{0.70f, 0.74f, 0.80f};  // linear 0..1; the default obstacle_color
};

// The names of the enumerations above, one base::EnumNames table each (the scene reader, the
// command line and the error messages all read these), in the order errors list them.
inline constexpr base::EnumNames<Shading, 3> shading_names{
    {{Shading::lit, "lit"}, {Shading::normals, "normals"}, {Shading::strain, "strain"}}};
inline constexpr base::EnumNames<RendererKind, 2> renderer_names{
    {{RendererKind::raster, "raster"}, {RendererKind::raytrace, "raytrace"}}};
inline constexpr base::EnumNames<GlBackend, 3> gl_backend_names{
    {{GlBackend::automatic, "auto"}, {GlBackend::osmesa, "osmesa"}, {GlBackend::egl, "egl"}}};

// The renderers' names, for a command-line option's check.
std::vector<std::string> renderer_choices();

const char* renderer_name(RendererKind kind);
const char* gl_backend_name(GlBackend backend);
// The value `name` names; otherwise throws std::invalid_argument starting with `where` and
// listing the choices ("render.gl: expected one of 'auto', 'osmesa', 'egl', got 'vulkan'").
RendererKind renderer_from_name(const std::string& name, const std::string& where);
GlBackend gl_backend_from_name(const std::string& name, const std::string& where);

}  // namespace weft::render
