#pragma once
// Intersection check for self-collision: counts the mesh edges that pass
// through a triangle of the same mesh in one configuration. A cloth that does not pass through
// itself has none; a fold pushed through the sheet has several per crossing line. Reported per
// frame in stats.csv (self_intersections) and used by tests. Detection only, no response.
//
// Counting rule (segment_crosses_triangle): an edge pq crosses triangle abc when p and q lie
// strictly on opposite sides of the triangle's plane and the line pq passes strictly inside the
// triangle — each of the five orientation predicates (signed volumes) must be farther from
// zero than the tolerance orientation_tolerance·L³, L the longest of pq, ab, bc, ca. Grazing
// and degenerate cases therefore do not count: an endpoint on (or within tolerance of) the
// plane, a coplanar edge, a line through a triangle's edge or vertex (such a crossing counts
// for neither neighbouring triangle), a degenerate triangle or edge. Edges and triangles that
// share a vertex are never tested (they always touch).

#include <array>
#include <vector>

#include "sim/types.h"

namespace weft::sim {

// Relative tolerance on the orientation predicates: a signed volume |V| ≤ tol·L³ counts as zero.
// Scale-invariant; about 1e4 times double rounding, so only genuinely grazing cases are dropped.
inline constexpr double orientation_tolerance = 1e-12;

// Whether segment pq passes through the interior of triangle abc (rule above). Positions, m.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                              const Vec3& c);

// The distinct undirected edges of a triangle list, each as (smaller, larger) vertex index,
// sorted lexicographically.
std::vector<std::array<Index, 2>> unique_edges(const std::vector<std::array<Index, 3>>& triangles);

struct EdgeTriangleCrossing {
  Index edge = 0;      // index into the edge list
  Index triangle = 0;  // index into the triangle list
  bool operator==(const EdgeTriangleCrossing& o) const {
    return edge == o.edge && triangle == o.triangle;
  }
};

// Every (edge, triangle) pair that crosses, sorted by edge then triangle. Broad phase: a
// spatial hash (sim/collision/spatial_hash.h) of the triangles' bounding boxes, cell size twice
// the mean largest box extent. x: #V×3 positions, metres; triangles and edges index rows of x.
// Throws std::invalid_argument if an index is out of range or a used position is not finite.
std::vector<EdgeTriangleCrossing> find_edge_triangle_crossings(
    const Matrix3X& x, const std::vector<std::array<Index, 3>>& triangles,
    const std::vector<std::array<Index, 2>>& edges);

// The same by testing all pairs: O(#E·#T), for tests.
std::vector<EdgeTriangleCrossing> find_edge_triangle_crossings_brute_force(
    const Matrix3X& x, const std::vector<std::array<Index, 3>>& triangles,
    const std::vector<std::array<Index, 2>>& edges);

// find_edge_triangle_crossings(...).size().
Index count_edge_triangle_crossings(const Matrix3X& x,
                                    const std::vector<std::array<Index, 3>>& triangles,
                                    const std::vector<std::array<Index, 2>>& edges);

}  // namespace weft::sim
