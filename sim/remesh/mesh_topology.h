#pragma once
// Topology of a triangle mesh given as plain arrays: input checks, vertex neighbours, boundary
// edges. Used by the curvature estimate (vertex rings) and the mesher (the boundary it keeps).

#include <array>
#include <vector>

#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

// Throws std::invalid_argument naming the item when the arrays do not form a mesh of the
// material domain; `what` names the mesh in the message ("remesh input"). Checked: at least
// one triangle, finite coordinates, indices in [0, #V), no triangle with zero material area.
void check_mesh(const Matrix2X& material, const Triangles& triangles, const char* what);

// Sorted, distinct neighbours of each vertex (vertices sharing an edge with it).
std::vector<std::vector<Index>> vertex_neighbours(Index vertex_count, const Triangles& triangles);

// The edges used by exactly one triangle, each as (a, b) in the triangle's own order, sorted.
// Throws std::invalid_argument naming the edge when an edge has more than two triangles.
std::vector<std::array<Index, 2>> boundary_edges(const Triangles& triangles);

// +1 when the triangles' material areas (u, v) are counter-clockwise, −1 when clockwise; throws
// std::invalid_argument when the triangles disagree (a mesh of inconsistent orientation).
int orientation(const Matrix2X& material, const Triangles& triangles);

// Twice the signed area of triangle (a, b, c) in the (u, v) plane, m².
inline double signed_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace weft::sim::remesh
