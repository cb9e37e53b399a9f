#pragma once
// OpenGL 3.3 core rasterizer: draws a RenderMesh off-screen into an Image, from the settings
// of the renderers' contract (render_settings.h), through a GlContext (gl_context.h). app/ does
// not include this header: it gets a renderer by name through renderer.h.

#include <memory>
#include <string>
#include <vector>

#include "render/gl_context.h"
#include "render/image.h"
#include "render/mask.h"
#include "render/render_mesh.h"
#include "render/render_settings.h"

namespace weft::render {

class RasterRenderer {
 public:
  // Takes ownership of a context; allocates GL resources lazily for each image size.
  explicit RasterRenderer(std::unique_ptr<GlContext> context);
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  // The cloth alone: render(mesh, settings, {}).
  Image render(const RenderMesh& mesh, const RenderSettings& settings);
  // The cloth and extra opaque objects. Throws std::invalid_argument for bad settings or a bad
  // mesh (an object's message starts "object k: ").
  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects);
  // The cloth's mask (cloth_only) or that of every surface, at the pixel centres, from the
  // geometry (Renderer::render_mask, render/renderer.h).
  Mask render_mask(const RenderMesh& cloth, const RenderSettings& settings,
                   const std::vector<RenderObject>& objects, bool cloth_only);
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace weft::render
