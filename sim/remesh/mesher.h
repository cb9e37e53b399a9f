#pragma once
// A new triangle mesh of a material domain, graded by a size field: CGAL's 2-D constrained
// Delaunay refinement (Delaunay_mesher_2, Shewchuk/Ruppert) with a sizing criterion. The
// domain is the union of the old mesh's triangles (holes and concave outlines included); every
// vertex of its boundary and every given vertex (pins) is a vertex of the new mesh at exactly
// the same (u, v); the boundary edges are constraints, split where the refinement needs.
// Interior vertices are otherwise new. CGAL is included only by mesher.cpp.

#include <functional>
#include <vector>

#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

// Target edge length (metres) at a material point; positive, finite.
using SizeFunction = std::function<double(const Vec2& material_point)>;

struct MesherParams {
  // The smallest angle a triangle may keep (degrees). Delaunay refinement is guaranteed to
  // terminate up to about 20.7° (CGAL's default bound B = sin² 20.7° = 0.125).
  double min_angle_deg = 20.0;
  // Stop with an error beyond this many vertices (a size field far too fine for the domain).
  Index max_vertices = 2'000'000;
};

struct MeshResult {
  Matrix2X material;              // #V_new×2, metres
  Triangles triangles;            // #T_new×3, oriented like the old mesh's triangles
  std::vector<Index> new_to_old;  // per new vertex: the old vertex it is (kept), or −1
};

// Meshes the domain of (material, triangles). keep: old vertices to keep besides the boundary
// (pins; duplicates and boundary vertices allowed). size: the target longest edge of a
// triangle, evaluated at its centroid; a triangle is refined while its longest edge exceeds it
// or its smallest angle is below min_angle_deg. Deterministic: the same input gives the same
// output bits. Throws std::invalid_argument naming the problem for a bad mesh, a bad parameter,
// a kept index out of range, or a size field that asks for more than max_vertices.
MeshResult mesh_domain(const Matrix2X& material, const Triangles& triangles,
                       const std::vector<Index>& keep, const SizeFunction& size,
                       const MesherParams& params = {});

}  // namespace weft::sim::remesh
