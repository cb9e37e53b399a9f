#pragma once
// The meeting point of sim and render: a cloth frame as a RenderMesh.

#include "render/render_mesh.h"
#include "sim/grid.h"
#include "sim/types.h"

namespace weft::app {

// Triangles of the grid at positions x (#V×3, m), with smooth normals and material (u, v) as UVs.
render::RenderMesh to_render_mesh(const sim::ClothMesh& mesh, const sim::Matrix3X& x);

}  // namespace weft::app
