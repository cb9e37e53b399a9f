#include "app/run/renderer_choice.h"

#include <cstdlib>

namespace weft::app {

render::GlBackend gl_backend_from_environment(render::GlBackend from_scene) {
  const char* variable = std::getenv("WEFT_GL");
  if (variable == nullptr || *variable == '\0') return from_scene;
  return render::gl_backend_from_name(variable, "environment variable WEFT_GL");
}

std::unique_ptr<render::Renderer> make_chosen_renderer(
    const render::RenderSettings& settings) {
  render::RenderSettings chosen = settings;
  chosen.gl = gl_backend_from_environment(settings.gl);
  return render::make_renderer(chosen);
}

}  // namespace weft::app
