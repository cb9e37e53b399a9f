// The renderers behind render/renderer.h's interface.

#include "render/renderer.h"

#include <stdexcept>
#include <utility>

#include "base/check.h"
#include "render/cloth_surface.h"
#include "render/raster.h"
#include "render/strain_colour.h"
#include "render/wireframe_overlay.h"

#ifdef WEFT_WITH_EMBREE_RT
#include "render/raytrace/ray_tracer.h"
#endif

namespace weft::render {

namespace {

// `mesh`, or a copy in `storage` whose wireframe edges are its triangle sides when it has none,
// taken before subdivision so that the lines stay those of the mesh given.
const RenderMesh& wireframe_mesh(const RenderMesh& mesh, RenderMesh& storage) {
  if (!mesh.edges.empty()) return mesh;
  storage = mesh;
  storage.edges = triangle_edges(mesh);
  return storage;
}

// The frame progress reports of a back-end: the ray tracer's tiles; the rasterizer has none.
template <class Backend>
void forward_frame_progress(Backend&, Renderer::FrameProgress) {}
#ifdef WEFT_WITH_EMBREE_RT
void forward_frame_progress(RayTracer& tracer, Renderer::FrameProgress progress) {
  tracer.set_frame_progress(std::move(progress));
}
#endif

// Either back-end behind the interface, the cloth's rendering aids (subdivision, thickness;
// render/cloth_surface.h) applied first, then the wireframe overlay over the frame and the
// strain legend last.
template <class Backend>
class WithClothSurface final : public Renderer {
 public:
  template <class... Args>
  explicit WithClothSurface(Args&&... args) : m_backend(std::forward<Args>(args)...) {}
  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects) override {
    RenderMesh storage, with_edges;
    const RenderMesh& drawn = prepare_cloth_mesh(
        settings.cloth_surface.wireframe.enabled ? wireframe_mesh(cloth, with_edges) : cloth,
        settings.cloth_surface, storage);
    Image image = m_backend.render(drawn, settings, objects);
    draw_wireframe(image, drawn, settings, objects);
    if (settings.shading == Shading::strain) draw_strain_legend(image, settings.strain_full_scale);
    return image;
  }
  Mask render_mask(const RenderMesh& cloth, const RenderSettings& settings,
                   const std::vector<RenderObject>& objects, MaskOf which) override {
    RenderMesh storage;
    return m_backend.render_mask(prepare_cloth_mesh(cloth, settings.cloth_surface, storage),
                                 settings, objects, which == MaskOf::cloth);
  }
  std::string description() const override { return m_backend.description(); }
  void set_frame_progress(FrameProgress progress) override {
    forward_frame_progress(m_backend, std::move(progress));
  }

 private:
  Backend m_backend;
};

}  // namespace

std::unique_ptr<Renderer> make_renderer(const RenderSettings& settings) {
  switch (settings.renderer) {
    case RendererKind::raster:
      return std::make_unique<WithClothSurface<RasterRenderer>>(
          make_gl_context(settings.gl, settings.width, settings.height));
    case RendererKind::raytrace:
#ifdef WEFT_WITH_EMBREE_RT
      return std::make_unique<WithClothSurface<RayTracer>>();
#else
      throw std::runtime_error(
          "renderer 'raytrace': weft was built without the ray tracer (CMake option "
          "WEFT_WITH_EMBREE_RT=OFF)");
#endif
  }
  WEFT_CHECK(false, "make_renderer: unknown RendererKind " +
                        std::to_string(static_cast<int>(settings.renderer)));
  return nullptr;
}

}  // namespace weft::render
