#pragma once
// Antialiased alpha for RGBA frames (`--background transparent`): how much of
// each pixel the surfaces cover, and the frame's edge colours freed of the background they were
// blended with, so that the frame composited over any background has soft edges without a
// fringe of the old background colour.

#include <cstdint>
#include <vector>

#include "render/image.h"
#include "render/renderer.h"

namespace weft::render {

// Sub-samples per pixel along each axis of the coverage: factor² samples on a regular grid.
// 4 (16 samples, 17 alpha levels) while the mask stays within 8192 pixels a side, else 2, else 1.
int coverage_factor(int width, int height);

// The fraction of each pixel the surfaces cover, 0..255 (row-major, top row first): the
// renderer's surfaces mask (Renderer::MaskOf::surfaces: cloth, objects and the ground inside
// its rim) drawn at coverage_factor()× the size with the same camera, averaged over each
// pixel's block. 255 where every sub-sample sees a surface, 0 where none does. Deterministic:
// the same bytes for any thread count, as the mask. Throws as Renderer::render_mask().
std::vector<std::uint8_t> surface_coverage(Renderer& renderer, const RenderMesh& cloth,
                                           const RenderSettings& settings,
                                           const std::vector<RenderObject>& objects);

// Where 0 < alpha < 255 the renderer drew P = a·C + (1 − a)·B (a = alpha/255, B the background
// colour, both renderers antialiasing by coverage); each such pixel becomes
// C = (P − (1 − a)·B)/a, rounded and clamped to 0..255. Other pixels are left as they are. The
// sizes must match (std::invalid_argument otherwise).
void unblend_background(Image& image, const std::vector<std::uint8_t>& alpha,
                        const Eigen::Vector3f& background);

}  // namespace weft::render
