// Self-collision response; the model and its limits are stated in self_collision.h.

#include "sim/collision/self_collision.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/collision/proximity.h"
#include "sim/collision/self_intersection.h"
#include "sim/collision/spatial_hash.h"

namespace weft::sim {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Vec3 row(const Matrix3X& x, Index v) { return x.row(v).transpose(); }

Aabb inflated(Aabb box, double by_m) {
  box.lo.array() -= by_m;
  box.hi.array() += by_m;
  return box;
}

// Weights within this of 0 count as on the triangle's boundary, not over its face.
constexpr double face_tolerance = 1e-9;

bool over_face(const Vec3& w) { return w.minCoeff() > face_tolerance; }

// Distance from p to triangle t of x.
double point_triangle_distance(const Matrix3X& x, Index p, const std::array<Index, 3>& t) {
  const Vec3 a = row(x, t[0]), b = row(x, t[1]), c = row(x, t[2]);
  const Vec3 w = closest_point_on_triangle_weights(row(x, p), a, b, c);
  return (row(x, p) - (w[0] * a + w[1] * b + w[2] * c)).norm();
}

double edge_edge_distance(const Matrix3X& x, const std::array<Index, 2>& e,
                          const std::array<Index, 2>& f) {
  const Vec3 p0 = row(x, e[0]), p1 = row(x, e[1]), q0 = row(x, f[0]), q1 = row(x, f[1]);
  const auto [s, t] = closest_segment_parameters(p0, p1, q0, q1);
  return ((p0 + s * (p1 - p0)) - (q0 + t * (q1 - q0))).norm();
}

bool shares_vertex(const std::array<Index, 2>& e, const std::array<Index, 2>& f) {
  return e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1];
}

// Projects one contact: constraint C = g − distance ≥ 0 along unit n, g the current gap along
// n, acting on up to four vertices with weights `w` (the gradient of g is w_k n). Returns
// whether it moved anything.
template <int N>
bool push_apart(const std::array<Index, N>& v, const std::array<double, N>& w, const Vec3& n,
                double gap_m, double distance_m, const Eigen::VectorXd& inv_mass, Matrix3X& x) {
  const double c = gap_m - distance_m;
  if (!(c < 0.0)) return false;
  double denominator = 0.0;
  for (int k = 0; k < N; ++k) denominator += w[k] * w[k] * inv_mass[v[k]];
  if (!(denominator > 0.0)) return false;  // every vertex involved is pinned
  const double lambda = -c / denominator;
  for (int k = 0; k < N; ++k) x.row(v[k]) += (lambda * w[k] * inv_mass[v[k]]) * n.transpose();
  return true;
}

}  // namespace

SelfCollision::SelfCollision(const ClothMesh& mesh, const SelfCollisionSettings& settings)
    : m_settings(settings), m_rest(mesh.rest_positions), m_triangles(mesh.triangles()) {
  if (!(settings.thickness_m > 0.0) || !std::isfinite(settings.thickness_m))
    throw std::invalid_argument("self_collision.thickness must be finite and > 0, got " +
                                std::to_string(settings.thickness_m) + " m");
  if (!(settings.marble_radius_m >= 0.0) || !std::isfinite(settings.marble_radius_m))
    throw std::invalid_argument("self_collision.marble_radius must be finite and >= 0, got " +
                                std::to_string(settings.marble_radius_m) + " m");
  if (settings.iterations < 1)
    throw std::invalid_argument("self_collision.iterations must be >= 1, got " +
                                std::to_string(settings.iterations));
  m_marble_radius_m =
      settings.marble_radius_m > 0.0 ? settings.marble_radius_m : 0.5 * settings.thickness_m;
  m_edges = unique_edges(m_triangles);
  for (const auto& t : m_triangles) m_vertices.insert(m_vertices.end(), t.begin(), t.end());
  std::sort(m_vertices.begin(), m_vertices.end());
  m_vertices.erase(std::unique(m_vertices.begin(), m_vertices.end()), m_vertices.end());
  // Neighbours: pairs closer at rest than the contact distance plus the mean rest edge are
  // never in contact, so a flat sheet has no candidates. Margin: half the mean rest edge, and
  // no less than the contact distance (larger: fewer rebuilds, longer lists; measured at 64²
  // with bench/self_collision_bench).
  double edge_sum_m = 0.0;
  for (const auto& e : m_edges) edge_sum_m += (row(m_rest, e[0]) - row(m_rest, e[1])).norm();
  const double mean_edge_m = m_edges.empty() ? 0.0 : edge_sum_m / static_cast<double>(m_edges.size());
  const double contact_m = std::max(settings.thickness_m, 2.0 * m_marble_radius_m);
  m_neighbourhood_m = mean_edge_m;
  m_margin_m = std::max(contact_m, 0.5 * mean_edge_m);
}

// Distances between features do not change when the whole cloth translates, so the list
// holds while every vertex's displacement since the build differs from one common vector c by
// at most half the margin: then each side of a pair has moved at most half the margin relative
// to c, and their distance has changed by at most the margin. c: the centre of the
// displacements' bounding box, which makes a falling cloth rebuild only as it deforms.
bool SelfCollision::needs_rebuild(const Matrix3X& x) const {
  if (!m_built || m_x_built.rows() != x.rows()) return true;
  Eigen::Array3d lo = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Array3d hi = -lo;
  for (const Index v : m_vertices) {
    const Eigen::Array3d d = (x.row(v) - m_x_built.row(v)).transpose().array();
    lo = lo.min(d);
    hi = hi.max(d);
  }
  const Eigen::RowVector3d c = (0.5 * (lo + hi)).matrix().transpose();
  const double limit2 = 0.25 * m_margin_m * m_margin_m;  // half the margin, squared
  for (const Index v : m_vertices)
    if ((x.row(v) - m_x_built.row(v) - c).squaredNorm() > limit2) return true;
  return false;
}

// Candidates: pairs within contact distance + margin at x that are not neighbours. A pair can come into contact only after some vertex has moved more than
// half the margin (each of its sides at most half), which triggers the next rebuild.
void SelfCollision::rebuild(const Matrix3X& x) {
  const auto start = Clock::now();
  const double t = m_settings.thickness_m, reach_m = t + m_margin_m;
  const double exclusion_m = exclusion_radius_m();
  const double marble_contact_m = 2.0 * m_marble_radius_m;
  m_candidates.vt.clear();
  m_candidates.ee.clear();
  m_candidates.vv.clear();
  std::vector<Index> ids;

  // Vertex–triangle: triangle boxes, queried with each vertex's box grown by the reach.
  std::vector<Aabb> boxes;
  boxes.reserve(m_triangles.size());
  double extent_sum_m = 0.0;
  for (const auto& tri : m_triangles) {
    boxes.push_back(bounding_box(row(x, tri[0]), row(x, tri[1]), row(x, tri[2])));
    extent_sum_m += (boxes.back().hi - boxes.back().lo).maxCoeff();
  }
  const double mean_extent_m =
      m_triangles.empty() ? 0.0 : extent_sum_m / static_cast<double>(m_triangles.size());
  const double cell_m = std::max(2.0 * mean_extent_m, reach_m);
  {
    const SpatialHash hash(cell_m, std::move(boxes));
    for (const Index v : m_vertices) {
      const Vec3 p = row(x, v);
      hash.query(inflated(Aabb{p, p}, reach_m), ids);
      for (const Index k : ids) {
        const auto& tri = m_triangles[static_cast<std::size_t>(k)];
        if (v == tri[0] || v == tri[1] || v == tri[2]) continue;
        if (point_triangle_distance(x, v, tri) < reach_m && point_triangle_distance(m_rest, v, tri) >= exclusion_m)
          m_candidates.vt.push_back({v, k});
      }
    }
  }
  // Edge–edge: edge boxes grown by half the reach each.
  boxes.clear();
  for (const auto& e : m_edges)
    boxes.push_back(inflated(bounding_box(row(x, e[0]), row(x, e[1])), 0.5 * reach_m));
  {
    const SpatialHash hash(cell_m, boxes);
    for (std::size_t i = 0; i < m_edges.size(); ++i) {
      hash.query(boxes[i], ids);
      for (const Index k : ids) {
        const auto j = static_cast<std::size_t>(k);
        if (j <= i || shares_vertex(m_edges[i], m_edges[j])) continue;
        if (edge_edge_distance(x, m_edges[i], m_edges[j]) < reach_m &&
            edge_edge_distance(m_rest, m_edges[i], m_edges[j]) >= exclusion_m)
          m_candidates.ee.push_back({static_cast<Index>(i), k});
      }
    }
  }
  // Vertex–vertex marbles.
  const double marble_reach_m = marble_contact_m + m_margin_m;
  boxes.clear();
  for (const Index v : m_vertices)
    boxes.push_back(inflated(Aabb{row(x, v), row(x, v)}, 0.5 * marble_reach_m));
  {
    const SpatialHash hash(std::max(cell_m, marble_reach_m), boxes);
    for (std::size_t i = 0; i < m_vertices.size(); ++i) {
      hash.query(boxes[i], ids);
      const Index a = m_vertices[i];
      for (const Index k : ids) {
        if (static_cast<std::size_t>(k) <= i) continue;
        const Index b = m_vertices[static_cast<std::size_t>(k)];
        if ((x.row(a) - x.row(b)).norm() < marble_reach_m &&
            (m_rest.row(a) - m_rest.row(b)).norm() >= marble_contact_m + m_neighbourhood_m)
          m_candidates.vv.push_back({a, b});
      }
    }
  }
  m_x_built = x;
  m_built = true;
  ++m_rebuilds;
  m_broad_s += seconds_since(start);
}

// Each contact kind: the pair's gap along its contact normal (side-aware, see the header),
// after pushing the pair apart if it was below the contact distance. A pair whose normal is
// undefined (degenerate triangle, coincident points) has an infinite gap.
double SelfCollision::project_vertex_triangle(const std::array<Index, 2>& pair,
                                              const Matrix3X& x_start,
                                              const Eigen::VectorXd& inv_mass, Matrix3X& x) const {
  constexpr double none = std::numeric_limits<double>::infinity();
  const double t = m_settings.thickness_m;
  const Index v = pair[0];
  const auto& tri = m_triangles[static_cast<std::size_t>(pair[1])];
  const Vec3 p = row(x, v), a = row(x, tri[0]), b = row(x, tri[1]), c = row(x, tri[2]);
  const Vec3 w = closest_point_on_triangle_weights(p, a, b, c);
  const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
  Vec3 n;
  double gap_m;
  if (over_face(w)) {
    const Vec3 normal = (b - a).cross(c - a);
    if (!(normal.squaredNorm() > 0.0)) return none;
    n = normal.normalized();
    // The side it was on when over the face at the start of the step; else where it is now.
    const Vec3 a0 = row(x_start, tri[0]), b0 = row(x_start, tri[1]), c0 = row(x_start, tri[2]);
    const Vec3 p0 = row(x_start, v);
    const double side0 = (p0 - a0).dot((b0 - a0).cross(c0 - a0));
    const bool was_over = over_face(closest_point_on_triangle_weights(p0, a0, b0, c0));
    const double side = was_over && side0 != 0.0 ? side0 : (p - q).dot(n);
    if (side < 0.0) n = -n;
    gap_m = (p - q).dot(n);
  } else {
    gap_m = (p - q).norm();
    if (!(gap_m > 0.0)) return none;
    n = (p - q) / gap_m;
  }
  push_apart<4>({v, tri[0], tri[1], tri[2]}, {1.0, -w[0], -w[1], -w[2]}, n, gap_m, t, inv_mass, x);
  return gap_m;
}

double SelfCollision::project_edge_edge(const std::array<Index, 2>& pair, const Matrix3X& x_start,
                                        const Eigen::VectorXd& inv_mass, Matrix3X& x) const {
  constexpr double none = std::numeric_limits<double>::infinity();
  const auto& e = m_edges[static_cast<std::size_t>(pair[0])];
  const auto& f = m_edges[static_cast<std::size_t>(pair[1])];
  const Vec3 p0 = row(x, e[0]), p1 = row(x, e[1]), q0 = row(x, f[0]), q1 = row(x, f[1]);
  const auto [s, u] = closest_segment_parameters(p0, p1, q0, q1);
  const Vec3 d = (p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0));
  // The same material points at the start of the step: if they swapped sides, the edges
  // passed through each other and go back to the start side.
  const Vec3 d0 = (row(x_start, e[0]) + s * (row(x_start, e[1]) - row(x_start, e[0]))) -
                  (row(x_start, f[0]) + u * (row(x_start, f[1]) - row(x_start, f[0])));
  const bool interior = s > 0.0 && s < 1.0 && u > 0.0 && u < 1.0;
  Vec3 n;
  if (interior && d.dot(d0) < 0.0 && d0.squaredNorm() > 0.0) {
    n = d0.normalized();
  } else {
    const double length = d.norm();
    if (!(length > 0.0)) return none;
    n = d / length;
  }
  const double gap_m = d.dot(n);
  push_apart<4>({e[0], e[1], f[0], f[1]}, {1.0 - s, s, u - 1.0, -u}, n, gap_m,
                m_settings.thickness_m, inv_mass, x);
  return gap_m;
}

double SelfCollision::project_marbles(const std::array<Index, 2>& pair,
                                      const Eigen::VectorXd& inv_mass, Matrix3X& x) const {
  const Vec3 d = row(x, pair[0]) - row(x, pair[1]);
  const double length = d.norm();
  if (!(length > 0.0)) return std::numeric_limits<double>::infinity();
  push_apart<2>(pair, {1.0, -1.0}, d / length, length, 2.0 * m_marble_radius_m, inv_mass, x);
  return length;
}

// One Gauss–Seidel sweep over `lists`; returns how many pairs were in contact. `near`, when
// given, collects the pairs within twice the contact distance: the later sweeps of the same
// call visit only those (a pair farther away is not reached by a few sweeps' small pushes; the
// next step's first sweep sees every candidate again).
int SelfCollision::sweep(const PairLists& lists, const Matrix3X& x_start,
                         const Eigen::VectorXd& inv_mass, Matrix3X& x, SelfContactCounts* counts,
                         PairLists* near) const {
  const double t = m_settings.thickness_m, marble_contact_m = 2.0 * m_marble_radius_m;
  int contacts = 0;
  const auto record = [&](double gap_m, double contact_m, long* count,
                          std::vector<std::array<Index, 2>>* near_list,
                          const std::array<Index, 2>& pair) {
    if (gap_m < contact_m) {
      ++contacts;
      if (counts) ++*count;
    }
    if (near && gap_m < 2.0 * contact_m) near_list->push_back(pair);
  };
  for (const auto& pair : lists.vt)
    record(project_vertex_triangle(pair, x_start, inv_mass, x), t,
           counts ? &counts->vertex_triangle : nullptr, near ? &near->vt : nullptr, pair);
  for (const auto& pair : lists.ee)
    record(project_edge_edge(pair, x_start, inv_mass, x), t, counts ? &counts->edge_edge : nullptr,
           near ? &near->ee : nullptr, pair);
  for (const auto& pair : lists.vv)
    record(project_marbles(pair, inv_mass, x), marble_contact_m,
           counts ? &counts->marbles : nullptr, near ? &near->vv : nullptr, pair);
  return contacts;
}

SelfContactCounts SelfCollision::resolve(const Matrix3X& x_start, const Eigen::VectorXd& inv_mass,
                                         Matrix3X& x) {
  if (x_start.rows() != x.rows() || inv_mass.size() != x.rows() || x.rows() != m_rest.rows())
    throw std::invalid_argument("SelfCollision::resolve: " + std::to_string(x.rows()) +
                                " positions, " + std::to_string(x_start.rows()) +
                                " start positions and " + std::to_string(inv_mass.size()) +
                                " inverse masses for a mesh of " + std::to_string(m_rest.rows()) +
                                " vertices");
  SelfContactCounts counts;
  if (needs_rebuild(x)) rebuild(x);
  const auto start = Clock::now();
  m_near.vt.clear();
  m_near.ee.clear();
  m_near.vv.clear();
  int contacts = sweep(m_candidates, x_start, inv_mass, x, &counts, &m_near);
  for (int i = 1; i < m_settings.iterations && contacts > 0; ++i)
    contacts = sweep(m_near, x_start, inv_mass, x, nullptr, nullptr);
  m_narrow_s += seconds_since(start);
  return counts;
}

}  // namespace weft::sim
