#pragma once
// The wireframe overlay (ClothSurface::wireframe): the simulation mesh's lines
// drawn over a finished frame, the same for both renderers. The Renderer interface
// (render/renderer.h) calls it on the cloth as drawn (after prepare_cloth_mesh: subdivision
// and the thickness shell carry RenderMesh::edges onto the surface they build).
//
// - Lines are width_px wide on screen whatever their depth, antialiased by coverage (the
//   distance from the pixel centre to the projected segment), and blended over the image in
//   the colour given; where lines meet, a pixel takes the largest coverage, not the sum.
// - Hidden lines: the cloth and the objects are scan-converted into a depth buffer (view
//   depth at pixel centres, the camera of the frame); a point of a line shows when it is no
//   deeper than the farthest surface in the 3×3 pixels about it plus a tolerance (0.2 % of
//   its depth and two pixels' footprint), so a line on the surface shows and one behind a
//   fold or an object does not. The ground hides no line. A segment with an end behind the
//   near plane is left out.

#include <vector>

#include "render/image.h"
#include "render/render_mesh.h"

namespace weft::render {

struct RenderSettings;
struct RenderObject;

// Draws settings.cloth_surface.wireframe over `image` (settings' size) when it is enabled:
// `cloth`'s edges, or every triangle side when it has none. Does nothing when disabled.
void draw_wireframe(Image& image, const RenderMesh& cloth, const RenderSettings& settings,
                    const std::vector<RenderObject>& objects);

}  // namespace weft::render
