#pragma once
// One interface for the renderers, chosen by RenderSettings::renderer: "raster" (OpenGL
// rasterizer, raster.h) or "raytrace" (Embree ray tracer, raytrace/ray_tracer.h, CMake option
// WEFT_WITH_EMBREE_RT). Both draw the cloth and objects of one frame from the same settings
// (the contract, render_settings.h); the cloth first goes through prepare_cloth_mesh
// (render/cloth_surface.h: subdivision, thickness shell). app/ includes this header and the
// contract only, never a back-end's.

#include <memory>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/render_mesh.h"
#include "render/render_settings.h"

namespace weft::render {

class Renderer {
 public:
  virtual ~Renderer() = default;
  // Throws std::invalid_argument for bad settings or meshes (an object's message starts
  // "object k: "), std::runtime_error when the back-end fails.
  virtual Image render(const RenderMesh& cloth, const RenderSettings& settings,
                       const std::vector<RenderObject>& objects) = 0;
  virtual std::string description() const = 0;
};

// The renderer settings.renderer names; the rasterizer gets the GL context settings.gl names
// (OSMesa or EGL; render/ reads no environment variable) of the settings' image size. Throws
// std::runtime_error when that back-end was not built or cannot start (e.g. no OSMesa
// context), saying which.
std::unique_ptr<Renderer> make_renderer(const RenderSettings& settings);

}  // namespace weft::render
