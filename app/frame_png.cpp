// One frame as an RGB or RGBA PNG (see frame_png.h).

#include "app/frame_png.h"

namespace weft::app {

render::Image render_frame_png(render::Renderer& renderer, const render::RenderMesh& cloth,
                               const render::RenderSettings& settings,
                               const std::vector<render::RenderObject>& objects, bool alpha,
                               const std::filesystem::path& path,
                               const std::function<void()>& before_write) {
  render::Image image = renderer.render(cloth, settings, objects);
  if (before_write) before_write();
  if (alpha)
    render::write_png(image,
                      renderer.render_mask(cloth, settings, objects,
                                           render::Renderer::MaskOf::surfaces),
                      path);
  else
    render::write_png(image, path);
  return image;
}

}  // namespace weft::app
