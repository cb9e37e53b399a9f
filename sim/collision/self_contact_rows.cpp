// Self-contact rows of a step; the model is stated in self_contact_rows.h.

#include "sim/collision/self_contact_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sim/collision/proximity.h"
#include "sim/collision/self_intersection.h"
#include "sim/collision/spatial_hash.h"

namespace weft::sim {
namespace {

// The barycentric weights of p's projection onto the plane of triangle abc (unclamped), or
// none (NaN) for a degenerate triangle.
Vec3 plane_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d00 = ab.dot(ab), d01 = ab.dot(ac), d11 = ac.dot(ac);
  const double d20 = ap.dot(ab), d21 = ap.dot(ac);
  const double det = d00 * d11 - d01 * d01;
  if (!(det > 0.0)) return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  const double wb = (d11 * d20 - d01 * d21) / det, wc = (d00 * d21 - d01 * d20) / det;
  return {1.0 - wb - wc, wb, wc};
}

Aabb swept_box(const Matrix3X& x0, const Matrix3X& x1, const Index* v, int count) {
  Aabb box{vertex(x0, v[0]), vertex(x0, v[0])};
  for (int k = 0; k < count; ++k) {
    for (const Matrix3X* x : {&x0, &x1}) {
      box.lo = box.lo.cwiseMin(vertex(*x, v[k]));
      box.hi = box.hi.cwiseMax(vertex(*x, v[k]));
    }
  }
  return box;
}

double mean_largest_extent(const std::vector<Aabb>& boxes) {
  double sum = 0.0;
  for (const Aabb& b : boxes) sum += (b.hi - b.lo).maxCoeff();
  return boxes.empty() ? 0.0 : sum / static_cast<double>(boxes.size());
}

}  // namespace

SelfContactRows::SelfContactRows(const ClothMesh& mesh, double distance_m,
                                 double neighbourhood_edges)
    : m_distance_m(distance_m),
      m_rest(mesh.rest_positions),
      m_triangles(mesh.triangles()),
      m_edges(unique_edges(m_triangles)) {
  if (!(distance_m > 0.0) || !std::isfinite(distance_m))
    throw std::invalid_argument("self_collision.thickness must be finite and > 0, got " +
                                std::to_string(distance_m) + " m");
  if (!(neighbourhood_edges >= 0.0 && neighbourhood_edges <= 4.0))
    throw std::invalid_argument("self_collision.neighbourhood must be in 0..4 edges, got " +
                                std::to_string(neighbourhood_edges));
  double sum = 0.0;
  for (const auto& e : m_edges) sum += (vertex(m_rest, e[0]) - vertex(m_rest, e[1])).norm();
  m_mean_edge_m = m_edges.empty() ? 0.0 : sum / static_cast<double>(m_edges.size());
  m_exclusion_m = distance_m + neighbourhood_edges * m_mean_edge_m;
  for (const auto& t : m_triangles) m_vertices.insert(m_vertices.end(), t.begin(), t.end());
  std::sort(m_vertices.begin(), m_vertices.end());
  m_vertices.erase(std::unique(m_vertices.begin(), m_vertices.end()), m_vertices.end());
}

void SelfContactRows::gather(const Matrix3X& x_start, const Matrix3X& x_end,
                             const Eigen::VectorXd& inv_mass, double slack_m) {
  m_rows.clear();
  if (m_triangles.empty()) return;
  const double reach_m = m_distance_m + slack_m;
  const auto all_pinned = [&](const std::array<Index, 4>& v) {
    return std::all_of(v.begin(), v.end(), [&](Index k) { return inv_mass[k] == 0.0; });
  };

  // Vertex–triangle: the triangles' swept boxes in a hash, each vertex's grown by the reach.
  std::vector<Aabb> boxes;
  boxes.reserve(m_triangles.size());
  for (const auto& t : m_triangles) boxes.push_back(swept_box(x_start, x_end, t.data(), 3));
  {
    const double cell_m = std::max(2.0 * mean_largest_extent(boxes), reach_m);
    const SpatialHash hash(cell_m, boxes);
    std::vector<Index> ids;
    for (const Index v : m_vertices) {
      hash.query(inflated(swept_box(x_start, x_end, &v, 1), reach_m), ids);
      const Vec3 p = vertex(x_start, v);
      for (const Index k : ids) {
        const auto& t = m_triangles[static_cast<std::size_t>(k)];
        if (v == t[0] || v == t[1] || v == t[2]) continue;
        const Vec3 a = vertex(x_start, t[0]), b = vertex(x_start, t[1]), c = vertex(x_start, t[2]);
        const Vec3 w = plane_weights(p, a, b, c);
        if (!(w.minCoeff() > -over_face_margin)) continue;  // not over the (grown) face
        Vec3 n = (b - a).cross(c - a);
        const double side = (p - a).dot(n);
        if (!(std::abs(side) > 0.0) || !(n.squaredNorm() > 0.0)) continue;
        const Vec3 r = vertex(m_rest, v);
        const Vec3 ra = vertex(m_rest, t[0]), rb = vertex(m_rest, t[1]), rc = vertex(m_rest, t[2]);
        const Vec3 wr = closest_point_on_triangle_weights(r, ra, rb, rc);
        const Vec3 qr = wr[0] * ra + wr[1] * rb + wr[2] * rc;
        if ((r - qr).norm() < m_exclusion_m) continue;  // neighbours never touch
        n.normalize();
        if (side < 0.0) n = -n;
        const SelfContactRow contact{{v, t[0], t[1], t[2]}, {1.0, -w[0], -w[1], -w[2]}, n};
        if (!all_pinned(contact.v)) m_rows.push_back(contact);
      }
    }
  }

  // Edge–edge: the edges' swept boxes in a hash, each edge's grown by the reach.
  boxes.clear();
  boxes.reserve(m_edges.size());
  for (const auto& e : m_edges) boxes.push_back(swept_box(x_start, x_end, e.data(), 2));
  const double cell_m = std::max(2.0 * mean_largest_extent(boxes), reach_m);
  const SpatialHash hash(cell_m, boxes);
  std::vector<Index> ids;
  for (std::size_t i = 0; i < m_edges.size(); ++i) {
    const auto& e = m_edges[i];
    hash.query(inflated(boxes[i], reach_m), ids);
    for (const Index j : ids) {
      if (static_cast<std::size_t>(j) <= i) continue;
      const auto& f = m_edges[static_cast<std::size_t>(j)];
      if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) continue;
      const Vec3 p0 = vertex(x_start, e[0]), p1 = vertex(x_start, e[1]);
      const Vec3 q0 = vertex(x_start, f[0]), q1 = vertex(x_start, f[1]);
      const auto [s, u] = closest_segment_parameters(p0, p1, q0, q1);
      if (!(s > 0.0 && s < 1.0 && u > 0.0 && u < 1.0)) continue;  // not inside both
      const Vec3 d = (p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0));
      if (!(d.squaredNorm() > 0.0)) continue;
      const auto [sr, ur] = closest_segment_parameters(vertex(m_rest, e[0]), vertex(m_rest, e[1]),
                                                       vertex(m_rest, f[0]), vertex(m_rest, f[1]));
      const Vec3 dr = (vertex(m_rest, e[0]) + sr * (vertex(m_rest, e[1]) - vertex(m_rest, e[0]))) -
                      (vertex(m_rest, f[0]) + ur * (vertex(m_rest, f[1]) - vertex(m_rest, f[0])));
      if (dr.norm() < m_exclusion_m) continue;  // neighbours never touch
      const SelfContactRow contact{{e[0], e[1], f[0], f[1]}, {1.0 - s, s, u - 1.0, -u}, d.normalized()};
      if (!all_pinned(contact.v)) m_rows.push_back(contact);
    }
  }
}

double SelfContactRows::worst_violation(const Matrix3X& x) const {
  double worst = 0.0;
  for (const SelfContactRow& r : m_rows) worst = std::min(worst, r.violation(x, m_distance_m, lateral_m()));
  return worst;
}

}  // namespace weft::sim
