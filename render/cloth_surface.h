#pragma once
// Rendering aids for the cloth, shared by both renderers (seed 003): Loop subdivision for a
// smooth surface from a coarse simulation mesh, an optional thickness shell ("quilting"), a
// texture mapped by material coordinates, the fabric's sheen, and a wireframe overlay of the
// simulation mesh's lines. RenderSettings::cloth_surface holds them; the Renderer interface (render/renderer.h)
// applies the mesh aids with prepare_cloth_mesh before either renderer draws and the wireframe
// (render/wireframe_overlay.h) after, and each renderer samples the texture (render/texture.h).

#include <Eigen/Core>

#include "render/render_mesh.h"
#include "render/texture.h"
#include "render/weave.h"

namespace weft::render {

// The simulation mesh's lines (RenderMesh::edges) drawn over the finished image: constant
// width on screen, antialiased, hidden where a surface is in front of them.
struct Wireframe {
  bool enabled = false;
  double width_px = 1.0;                       // line width in pixels, > 0
  Eigen::Vector3f color{0.08f, 0.08f, 0.08f};  // 0..1, as the image's other colours
};

struct ClothSurface {
  int subdivision_levels = 0;  // Loop levels, 0..3 (render/loop_subdivision.h)
  double thickness_m = 0.0;    // 0: a single two-sided sheet; > 0: a closed shell this thick
  ClothTexture texture;        // no image: the plain front colour
  // The sheen lobe (render/sheen.h) added to the cloth's diffuse reflection in both renderers:
  // weight 0 (off) .. 1, and the roughness of its distribution, (0, 1].
  double sheen = 0.5;
  double sheen_roughness = 0.5;
  Weave weave;  // no normal map: no weave relief
  Wireframe wireframe;         // off by default
};

// Throws std::invalid_argument naming the field ("RenderSettings: cloth_surface.…") unless
// levels are in 0..3 and the thickness is finite and ≥ 0, and a texture, when given, is not
// empty and repeats over finite lengths > 0, the sheen is in [0, 1] and its roughness in
// (0, 1], and an enabled wireframe's width is finite and > 0 and its colour within 0..1.
void validate(const ClothSurface& surface);

// The cloth as drawn: `mesh` subdivided, then thickened. Returns `mesh` itself when there is
// nothing to do, else the result built in `storage`.
const RenderMesh& prepare_cloth_mesh(const RenderMesh& mesh, const ClothSurface& surface,
                                     RenderMesh& storage);

}  // namespace weft::render
