#pragma once
// Loop subdivision of a RenderMesh (Loop 1987, "Smooth Subdivision Surfaces Based on
// Triangles"): each level splits every triangle into four and moves the vertices by Loop's
// masks, so a coarse simulation mesh renders as a smooth surface (seed 003, "subdivision").
//
// One level, V vertices, E edges, F triangles → V + E vertices, 4F triangles. The old vertices
// keep their indices 0..V−1; edge points follow in the order the edges are first met.
//   interior edge ab with opposite vertices c, d:   3/8 (a + b) + 1/8 (c + d)
//   interior vertex v of valence n, neighbours q_i: (1 − n β) v + β Σ q_i,
//                                                   β = (5/8 − (3/8 + 1/4 cos(2π/n))²) / n
//   boundary edge ab (one face):                    (a + b) / 2
//   boundary vertex v between boundary neighbours a, b: 3/4 v + 1/8 (a + b)
//     (the edge and vertex masks of the cubic B-spline: the boundary is a curve of its own)
//   corners, kept where they are: boundary vertices in fewer than 3 triangles (a rectangle's
//     corners; a regular boundary vertex is in 3), and vertices on more than two boundary
//     edges or on an edge shared by more than two triangles (non-manifold).
// UVs (material coordinates): old vertices keep theirs, edge points take the mean of the
// edge's two ends (linear interpolation, exact wherever the UVs are a linear map of the rest
// mesh, as on the cloth grid). Normals are recomputed (compute_vertex_normals). The wireframe
// edges (RenderMesh::edges) are split at their edge points, so they stay sides of triangles
// of the subdivided mesh and lie on its surface; an edge that is no triangle's side is an error.

#include "render/render_mesh.h"

namespace weft::render {

inline constexpr int max_subdivision_levels = 3;

// `levels` Loop steps of `mesh` (0: a copy, normals computed when missing). Throws
// std::invalid_argument unless 0 ≤ levels ≤ max_subdivision_levels, the mesh is valid
// (validate) and its UVs are empty or one per vertex, and the result fits 32-bit indices.
RenderMesh loop_subdivide(const RenderMesh& mesh, int levels);

}  // namespace weft::render
