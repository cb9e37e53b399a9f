#include "sim/collision/self_intersection.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/collision/spatial_hash.h"

namespace weft::sim {
namespace {

// Sign of the orientation predicate: +1, −1, or 0 when |V| ≤ eps. V = det[b−a, c−a, d−a] is
// six times the signed volume of tetrahedron abcd (Shewchuk 1997, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", orient3d, opposite sign).
int orientation_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double eps) {
  const double volume = (b - a).cross(c - a).dot(d - a);
  return volume > eps ? 1 : (volume < -eps ? -1 : 0);
}

bool shares_vertex(const std::array<Index, 2>& edge, const std::array<Index, 3>& triangle) {
  for (const Index t : triangle)
    if (t == edge[0] || t == edge[1]) return true;
  return false;
}

void check_indices(const Matrix3X& x, const std::vector<std::array<Index, 3>>& triangles,
                   const std::vector<std::array<Index, 2>>& edges) {
  const Index n = static_cast<Index>(x.rows());
  const auto check = [&](Index v, const char* what, std::size_t k) {
    if (v < 0 || v >= n)
      throw std::invalid_argument(std::string("self-intersection: ") + what + " " +
                                  std::to_string(k) + " has vertex " + std::to_string(v) +
                                  ", outside 0.." + std::to_string(n - 1));
    if (!x.row(v).allFinite())
      throw std::invalid_argument("self-intersection: vertex " + std::to_string(v) +
                                  " has a non-finite position");
  };
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (const Index v : triangles[t]) check(v, "triangle", t);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (const Index v : edges[e]) check(v, "edge", e);
}

bool edge_crosses(const Matrix3X& x, const std::array<Index, 2>& edge,
                  const std::array<Index, 3>& triangle) {
  return segment_crosses_triangle(vertex(x, edge[0]), vertex(x, edge[1]), vertex(x, triangle[0]),
                                  vertex(x, triangle[1]), vertex(x, triangle[2]));
}

}  // namespace

bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                              const Vec3& c) {
  // Work relative to p so that a translated configuration rounds like the original.
  const Vec3 qr = q - p, ar = a - p, br = b - p, cr = c - p, o = Vec3::Zero();
  const double length_m = std::max({qr.norm(), (br - ar).norm(), (cr - br).norm(), (ar - cr).norm()});
  const double eps = orientation_tolerance * length_m * length_m * length_m;
  // p and q strictly on opposite sides of the plane of abc.
  const int side_p = orientation_sign(ar, br, cr, o, eps);
  const int side_q = orientation_sign(ar, br, cr, qr, eps);
  if (side_p == 0 || side_q == 0 || side_p == side_q) return false;
  // The line pq passes the three edges of abc on the same side: strictly inside.
  const int s_ab = orientation_sign(o, qr, ar, br, eps);
  const int s_bc = orientation_sign(o, qr, br, cr, eps);
  const int s_ca = orientation_sign(o, qr, cr, ar, eps);
  return s_ab != 0 && s_ab == s_bc && s_bc == s_ca;
}

std::vector<std::array<Index, 2>> unique_edges(const std::vector<std::array<Index, 3>>& triangles) {
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<EdgeTriangleCrossing> find_edge_triangle_crossings(
    const Matrix3X& x, const std::vector<std::array<Index, 3>>& triangles,
    const std::vector<std::array<Index, 2>>& edges) {
  check_indices(x, triangles, edges);
  std::vector<Aabb> boxes;
  boxes.reserve(triangles.size());
  double extent_sum_m = 0.0;
  for (const auto& t : triangles) {
    boxes.push_back(bounding_box(vertex(x, t[0]), vertex(x, t[1]), vertex(x, t[2])));
    extent_sum_m += (boxes.back().hi - boxes.back().lo).maxCoeff();
  }
  const double mean_extent_m = triangles.empty() ? 0.0 : extent_sum_m / static_cast<double>(triangles.size());
  // Cells twice the mean triangle extent: measured fastest at 64² (fewer cells per box to fill
  // and visit; about the same candidates per edge).
  const SpatialHash hash(mean_extent_m > 0.0 ? 2.0 * mean_extent_m : 1.0, std::move(boxes));

  std::vector<EdgeTriangleCrossing> crossings;
  std::vector<Index> candidates;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& edge = edges[e];
    hash.query(bounding_box(vertex(x, edge[0]), vertex(x, edge[1])), candidates);
    for (const Index t : candidates) {
      const auto& triangle = triangles[static_cast<std::size_t>(t)];
      if (!shares_vertex(edge, triangle) && edge_crosses(x, edge, triangle))
        crossings.push_back({static_cast<Index>(e), t});
    }
  }
  return crossings;
}

std::vector<EdgeTriangleCrossing> find_edge_triangle_crossings_brute_force(
    const Matrix3X& x, const std::vector<std::array<Index, 3>>& triangles,
    const std::vector<std::array<Index, 2>>& edges) {
  check_indices(x, triangles, edges);
  std::vector<EdgeTriangleCrossing> crossings;
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (std::size_t t = 0; t < triangles.size(); ++t)
      if (!shares_vertex(edges[e], triangles[t]) && edge_crosses(x, edges[e], triangles[t]))
        crossings.push_back({static_cast<Index>(e), static_cast<Index>(t)});
  return crossings;
}

Index count_edge_triangle_crossings(const Matrix3X& x,
                                    const std::vector<std::array<Index, 3>>& triangles,
                                    const std::vector<std::array<Index, 2>>& edges) {
  return static_cast<Index>(find_edge_triangle_crossings(x, triangles, edges).size());
}

}  // namespace weft::sim
