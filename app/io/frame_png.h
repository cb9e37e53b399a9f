#pragma once
// One rendered frame written as a PNG, shared by `weft run` and `weft turntable`: RGB, or with
// `alpha` (output.alpha, `--background transparent`) RGBA: alpha the share of the pixel the
// surfaces cover (render/coverage_alpha.h: 16 samples a pixel, so edges are antialiased), the
// edge colours freed of the plain background colour they were blended with.

#include <filesystem>
#include <functional>
#include <vector>

#include "render/image.h"
#include "render/renderer.h"

namespace weft::app {

// Renders the frame, calls `before_write` (if given: e.g. preparing the output folder once the
// first image exists), writes it to `path` and returns the image (RGB).
render::Image render_frame_png(render::Renderer& renderer, const render::RenderMesh& cloth,
                               const render::RenderSettings& settings,
                               const std::vector<render::RenderObject>& objects, bool alpha,
                               const std::filesystem::path& path,
                               const std::function<void()>& before_write = {});

}  // namespace weft::app
