#pragma once
// Closest-point kernels shared by the collision code: point–triangle and segment–segment.
// Pure functions of positions (metres); no allocation.

#include <array>

#include "sim/types.h"

namespace weft::sim {

// The point of triangle abc nearest p, as barycentric weights (w_a, w_b, w_c), each ≥ 0,
// summing to 1; the point itself is w_a a + w_b b + w_c c. Exact case analysis over the seven
// Voronoi regions of the triangle (vertices, edges, face; Ericson 2005, "Real-Time Collision
// Detection", §5.1.5). A degenerate triangle (collinear or coincident corners) gives the
// nearest point of its longest edge.
Vec3 closest_point_on_triangle_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// The closest points of segments p0p1 and q0q1 as parameters (s, t) ∈ [0, 1]²: the points
// p0 + s (p1 − p0) and q0 + t (q1 − q0). Parallel segments (and degenerate ones) give one of
// the closest pairs, chosen deterministically (Ericson 2005, §5.1.9).
std::array<double, 2> closest_segment_parameters(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                                 const Vec3& q1);

}  // namespace weft::sim
