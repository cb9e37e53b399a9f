#pragma once
// A disc specimen with a smooth edge (cloth.edge "smooth", docs/scene.md): the ellipse inscribed
// in the size_u_m × size_v_m rectangle (a circle when the two are equal), meshed in concentric
// rings of triangles whose outer ring lies on the ellipse. The grid's disc (the cells whose
// centre is inside) has an edge that is a staircase of cells, which shows in the outline the
// drape is read from; the rings' edge is a polygon of 6N vertices on the ellipse.
//
// It is a triangle mesh without a warp/weft grid, made through the path of a mesh file
// (make_pattern_cloth, sim/triangle_cloth.h), so every model and measure runs on it as on a mesh
// file (docs/meshes.md): the warp is +u in the material coordinates the models read, not a line
// of vertices. Why rings and not a grid whose edge vertices are moved onto the circle:
// docs/meshes.md, "A disc with a smooth edge".

#include "sim/grid.h"

namespace weft::sim {

// The number of rings N = ⌈(max(nu, nv) − 1)/2⌉ (at least 1): the rings' spacing along each
// axis, a/N and b/N, is at most the grid's, size/(n − 1), so that `resolution` [61, 61] gives
// 30 rings 5 mm apart on a Ø30 cm disc, as its grid has 5 mm cells.
Index round_specimen_rings(const GridSpec& spec);

// The ring mesh of spec's ellipse (semi-axes a = size_u_m/2, b = size_v_m/2, centred at
// material point (a, b), so placed like the grid's disc by origin, warp_axis and weft_axis;
// spec.shape and spec.disc_edge are not read). Vertex 0 is the centre; ring k = 1..N has the 6k
// vertices 1 + 3k(k − 1) + m, m = 0..6k − 1, at material point
// (a + a (k/N) cos φ, b + b (k/N) sin φ), φ = 2πm/(6k): equally spaced in the parametric angle,
// counter-clockwise from +u, m = 0 on the +u axis. Rings k − 1 and k are joined by 12k − 6
// triangles, each ring stepping to its next vertex when that comes first in angle (the inner
// ring on a tie, at the six spokes φ = 60°·s): 6N² triangles in all, counter-clockwise in (u, v).
// Lumped areas: a third of each triangle's (make_pattern_cloth). Throws std::invalid_argument for a
// resolution below 2 × 2 or a size that is not positive and finite.
ClothMesh make_round_specimen(const GridSpec& spec);

}  // namespace weft::sim
