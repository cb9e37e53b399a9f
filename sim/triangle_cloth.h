#pragma once
// A cloth mesh from a flat pattern of polygons (a mesh file: app/io/cloth_mesh_file.h): each
// vertex's material coordinates (the flat pattern, metres, u along the warp) and its start
// position, and the polygons joining them.
//
// When every polygon is a quad and the quads are the cells of a regular warp/weft lattice in
// material coordinates (axis-aligned, equally spaced, counter-clockwise), the mesh is that
// grid (make_grid_cells), numbered as the grid is (vertex (i, j) at j·nu + i, lattice points
// of no quad unused), and every model and the projection run on it exactly as on the built-in
// grid. Otherwise it is a triangle mesh (no grid): each polygon fanned from its first corner.
// Each vertex's lumped area is a third of each of its triangles' areas (a grid's: a quarter of
// each of its cells').
//
// Checked, each an std::invalid_argument naming the face, edge or vertex (the caller puts the
// file's name before it): a polygon with (near) zero area in material coordinates (≤ 1e-10 of
// the squared size of the pattern), a polygon that is not convex there (its fan would fold),
// an edge shared by more than two faces (non-manifold), two faces overlapping in material
// coordinates (a fold in the UV map or the flattening: an edge both faces run the same way
// once each is turned counter-clockwise), and positions that are not finite.

#include <string>
#include <vector>

#include "sim/grid.h"

namespace weft::sim {

struct ClothPattern {
  std::vector<Vec2> material_coords;       // #V (u, v), metres
  Matrix3X start_positions;                // #V×3, metres: where the simulation starts
  std::vector<std::vector<Index>> faces;   // polygons of ≥ 3 corners, either orientation
  // Where the flat pattern is laid as the rest shape: (u, v) at origin + u·warp + v·weft.
  Vec3 origin{0.0, 0.0, 0.0};
  Vec3 warp_axis{1.0, 0.0, 0.0};
  Vec3 weft_axis{0.0, 1.0, 0.0};
  std::string source;  // ClothMesh::source
};

ClothMesh make_pattern_cloth(const ClothPattern& pattern);

}  // namespace weft::sim
