#pragma once
// The meeting point of sim and render: a cloth frame as a RenderMesh.

#include <vector>

#include "render/render_mesh.h"
#include "sim/grid.h"
#include "sim/types.h"

namespace weft::app {

// Triangles of the grid at positions x (#V×3, m), with smooth normals, material (u, v) as UVs
// and vertex_strains as the strain (render::Shading::strain); a grid's warp and weft edges as
// the wireframe's lines (RenderMesh::edges; none for a mesh without a grid: all its sides).
render::RenderMesh to_render_mesh(const sim::ClothMesh& mesh, const sim::Matrix3X& x);

// #V: the mean strain (length/rest − 1) of the warp and weft edges at each vertex, at x (#V×3, m);
// 0 for a vertex on no edge.
std::vector<double> vertex_strains(const sim::ClothMesh& mesh, const sim::Matrix3X& x);

}  // namespace weft::app
