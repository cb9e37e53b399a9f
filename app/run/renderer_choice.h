#pragma once
// The renderer a command draws with: the scene's render settings, with the environment's say
// on the rasterizer's GL context. The environment variable WEFT_GL (osmesa|egl|auto) is read
// here, in app/, and handed to render/ through RenderSettings::gl; render/ reads no
// environment.

#include <memory>

#include "render/renderer.h"
#include "render/render_settings.h"

namespace weft::app {

// WEFT_GL's choice when it is set and not empty, else `from_scene` (render.gl). Throws
// std::invalid_argument naming "environment variable WEFT_GL" and the choices for a bad value.
render::GlBackend gl_backend_from_environment(render::GlBackend from_scene);

// render::make_renderer(settings) with settings.gl from gl_backend_from_environment. Throws as
// both do.
std::unique_ptr<render::Renderer> make_chosen_renderer(
    const render::RenderSettings& settings);

}  // namespace weft::app
