// The renderers behind render/renderer.h's interface.

#include "render/renderer.h"

#include <stdexcept>

#include "render/cloth_surface.h"

#ifdef WEFT_WITH_EMBREE_RT
#include "render/raytrace/ray_tracer.h"
#endif

namespace weft::render {

namespace {

class Raster final : public Renderer {
 public:
  explicit Raster(const RenderSettings& s)
      : m_renderer(make_gl_context(s.gl, s.width, s.height)) {}
  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects) override {
    RenderMesh storage;
    return m_renderer.render(prepare_cloth_mesh(cloth, settings.cloth_surface, storage), settings,
                             objects);
  }
  std::string description() const override { return m_renderer.description(); }

 private:
  RasterRenderer m_renderer;
};

#ifdef WEFT_WITH_EMBREE_RT
class RayTrace final : public Renderer {
 public:
  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects) override {
    RenderMesh storage;
    return m_tracer.render(prepare_cloth_mesh(cloth, settings.cloth_surface, storage), settings,
                           objects);
  }
  std::string description() const override { return m_tracer.description(); }

 private:
  RayTracer m_tracer;
};
#endif

}  // namespace

const char* renderer_name(RendererKind kind) {
  return kind == RendererKind::raytrace ? "raytrace" : "raster";
}

std::unique_ptr<Renderer> make_renderer(const RenderSettings& settings) {
  switch (settings.renderer) {
    case RendererKind::raster:
      return std::make_unique<Raster>(settings);
    case RendererKind::raytrace:
#ifdef WEFT_WITH_EMBREE_RT
      return std::make_unique<RayTrace>();
#else
      throw std::runtime_error(
          "renderer 'raytrace': weft was built without the ray tracer (CMake option "
          "WEFT_WITH_EMBREE_RT=OFF)");
#endif
  }
  throw std::logic_error("make_renderer: unknown RendererKind");
}

}  // namespace weft::render
