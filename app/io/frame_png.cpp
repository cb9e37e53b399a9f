// One frame as an RGB or RGBA PNG (see frame_png.h).

#include "app/io/frame_png.h"

#include "render/coverage_alpha.h"

namespace weft::app {

render::Image render_frame_png(render::Renderer& renderer, const render::RenderMesh& cloth,
                               const render::RenderSettings& settings,
                               const std::vector<render::RenderObject>& objects, bool alpha,
                               const std::filesystem::path& path,
                               const std::function<void()>& before_write) {
  render::Image image = renderer.render(cloth, settings, objects);
  if (!alpha) {
    if (before_write) before_write();
    render::write_png(image, path);
    return image;
  }
  const std::vector<std::uint8_t> coverage =
      render::surface_coverage(renderer, cloth, settings, objects);
  if (before_write) before_write();
  // A plain background colour can be taken out of the edges; an environment map's cannot.
  render::Image colours = image;
  if (!(settings.environment.map && settings.environment.background))
    render::unblend_background(colours, coverage, settings.background);
  render::write_png(colours, coverage, path);
  return image;
}

}  // namespace weft::app
