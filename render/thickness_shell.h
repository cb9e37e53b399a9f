#pragma once
// Optional cloth thickness (seed 003's "quilting"): a single-sheet RenderMesh turned into a
// closed shell, so that the cloth reads as a solid of some thickness rather than a sheet of
// zero thickness.
//
// With unit vertex normals n (computed when missing) and thickness t:
//   vertices 0..V−1    the upper sheet, p + (t/2) n (the side the front faces),
//   vertices V..2V−1   the lower sheet, p − (t/2) n,
//   triangles          the mesh's triangles on each sheet, then two per boundary edge joining
//                      the sheets (a strip of quads around the rim, facing outward).
// The lower sheet keeps the winding of the upper one, so that from outside it shows the
// cloth's back side (RenderSettings::back_color) as the single sheet did: the shell is closed
// (every edge in exactly two triangles when the input is a manifold with boundary) but not
// consistently oriented, which two-sided renderers do not mind. UVs and the wireframe edges
// (RenderMesh::edges) are copied to both sheets.
// Normals are recomputed over the whole shell. Folds tighter than t/2 make the offset sheets
// cross each other; keep t well below the fold radius.

#include "render/render_mesh.h"

namespace weft::render {

// Throws std::invalid_argument unless thickness_m is finite and > 0, the mesh is valid
// (validate), its UVs are empty or one per vertex, and 2V fits 32-bit indices.
RenderMesh make_thickness_shell(const RenderMesh& mesh, double thickness_m);

}  // namespace weft::render
