#pragma once
// One interface for the renderers, chosen by name: "raster" (OSMesa rasterizer, raster.h) or
// "raytrace" (Embree ray tracer, raytrace/ray_tracer.h, CMake option WEFT_WITH_EMBREE_RT).
// Both draw the cloth and objects of one frame from the same RenderSettings; the cloth first
// goes through prepare_cloth_mesh (render/cloth_surface.h: subdivision, thickness shell).

#include <memory>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/raster.h"
#include "render/render_mesh.h"

namespace weft::render {

class Renderer {
 public:
  virtual ~Renderer() = default;
  // Throws std::invalid_argument for bad settings or meshes (as RasterRenderer::render).
  virtual Image render(const RenderMesh& cloth, const RenderSettings& settings,
                       const std::vector<RenderObject>& objects) = 0;
  virtual std::string description() const = 0;
};

// "raster" or "raytrace".
const char* renderer_name(RendererKind kind);

// The renderer settings.renderer names; the rasterizer gets the GL context settings.gl names
// (OSMesa or EGL, make_gl_context: WEFT_GL overrides) of the settings' image size. Throws std::runtime_error when that back-end was not built or cannot start
// (e.g. no OSMesa context), saying which.
std::unique_ptr<Renderer> make_renderer(const RenderSettings& settings);

}  // namespace weft::render
