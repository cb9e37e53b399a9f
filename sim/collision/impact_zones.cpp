#include "sim/collision/impact_zones.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "sim/collision/continuous_collision.h"
#include "sim/collision/self_intersection.h"
#include "sim/collision/spatial_hash.h"

namespace weft::sim {
namespace {

Aabb swept_box(const Matrix3X& x_start, const Matrix3X& x, const Index* ids, int count,
               double grow_m) {
  Aabb box{vertex(x_start, ids[0]), vertex(x_start, ids[0])};
  for (int k = 0; k < count; ++k)
    for (const Matrix3X* m : {&x_start, &x}) {
      const Vec3 p = vertex(*m, ids[k]);
      box.lo = box.lo.cwiseMin(p);
      box.hi = box.hi.cwiseMax(p);
    }
  return inflated(box, grow_m);
}

double zone_cell_size(const std::vector<Aabb>& boxes) {
  double sum_m = 0.0;
  for (const Aabb& b : boxes) sum_m += (b.hi - b.lo).maxCoeff();
  const double mean_m = boxes.empty() ? 0.0 : sum_m / static_cast<double>(boxes.size());
  return mean_m > 0.0 ? 2.0 * mean_m : 1.0;  // as the crossing count (self_intersection.cpp)
}

// The masses of n vertices for the rigid zone motions: 1 / inv_mass, and a million times the
// heaviest vertex (at least 1 kg) at the pins (inverse mass 0).
Eigen::VectorXd impact_zone_masses(const Eigen::VectorXd& inv_mass, std::size_t n) {
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  double heaviest_kg = 0.0;
  for (Eigen::Index v = 0; v < inv_mass.size(); ++v)
    if (inv_mass[v] > 0.0) heaviest_kg = std::max(heaviest_kg, 1.0 / inv_mass[v]);
  for (Eigen::Index v = 0; v < inv_mass.size(); ++v)
    mass[v] = inv_mass[v] > 0.0 ? 1.0 / inv_mass[v] : 1e6 * std::max(heaviest_kg, 1.0);
  return mass;
}

// The least altitude of the mesh's triangles at rest. On a flat grid, a vertex is at least this
// far from a triangle, and an edge from an edge, that it shares no vertex with: the segment
// between them leaves the vertex's star through the opposite sides of its triangles.
double least_rest_altitude(const ClothMesh& mesh, const std::vector<std::array<Index, 3>>& triangles) {
  double least_m = std::numeric_limits<double>::infinity();
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = vertex(mesh.rest_positions, t[k]);
      const Vec3 b = vertex(mesh.rest_positions, t[(k + 1) % 3]);
      const Vec3 c = vertex(mesh.rest_positions, t[(k + 2) % 3]);
      least_m = std::min(least_m, (b - a).cross(c - a).norm() / (c - b).norm());
    }
  return std::isfinite(least_m) ? least_m : 0.0;
}

}  // namespace

void apply_rigid_zone_motion(const std::vector<Index>& zone, const Matrix3X& x_start,
                             const Matrix3X& x_proposed, const Eigen::VectorXd& mass,
                             Matrix3X& x) {
  if (zone.empty()) return;
  double total_kg = 0.0;
  Vec3 c0 = Vec3::Zero(), c1 = Vec3::Zero();
  for (const Index v : zone) {
    total_kg += mass[v];
    c0 += mass[v] * vertex(x_start, v);
    c1 += mass[v] * vertex(x_proposed, v);
  }
  c0 /= total_kg;
  c1 /= total_kg;
  Vec3 momentum = Vec3::Zero();  // angular, of the displacements about c0 (kg m²)
  Mat3 inertia = Mat3::Zero();
  for (const Index v : zone) {
    const Vec3 r = vertex(x_start, v) - c0;
    const Vec3 d = vertex(x_proposed, v) - vertex(x_start, v);
    momentum += mass[v] * r.cross(d);
    inertia += mass[v] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  }
  // ω = I⁻¹ L, by the pseudo-inverse: a collinear zone has no inertia about its line.
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
  const Vec3 values = eigen.eigenvalues();
  const double cutoff = 1e-12 * values.cwiseAbs().maxCoeff();
  Vec3 in_basis = eigen.eigenvectors().transpose() * momentum;
  for (int k = 0; k < 3; ++k) in_basis[k] = values[k] > cutoff ? in_basis[k] / values[k] : 0.0;
  const Vec3 omega = eigen.eigenvectors() * in_basis;
  const double angle = omega.norm();
  const Mat3 rotation =
      angle > 0.0 ? Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix() : Mat3::Identity();
  for (const Index v : zone) x.row(v) = (c1 + rotation * (vertex(x_start, v) - c0)).transpose();
}

ImpactZones::ImpactZones(std::vector<std::array<Index, 3>> triangles, double eta_m)
    : m_triangles(std::move(triangles)), m_edges(unique_edges(m_triangles)), m_eta_m(eta_m) {
  if (!(eta_m > 0.0) || !std::isfinite(eta_m))
    throw std::invalid_argument("impact zones: the thickness eta must be finite > 0");
  for (const auto& t : m_triangles) m_vertices.insert(m_vertices.end(), t.begin(), t.end());
  std::sort(m_vertices.begin(), m_vertices.end());
  m_vertices.erase(std::unique(m_vertices.begin(), m_vertices.end()), m_vertices.end());
}

ImpactZones::ImpactZones(const ClothMesh& mesh, double eta_m)
    : ImpactZones(mesh.triangles(), eta_m) {
  if (!mesh.has_grid()) return;
  m_patches = std::make_unique<SurfacePatches>(mesh, m_triangles, m_edges, patch_cells_per_side);
  m_culling.exclusion_m = least_rest_altitude(mesh, m_triangles);
}

ImpactZones::~ImpactZones() = default;

Index ImpactZones::find(Index v) {
  Index root = v;
  while (m_parent[static_cast<std::size_t>(root)] != root)
    root = m_parent[static_cast<std::size_t>(root)];
  while (m_parent[static_cast<std::size_t>(v)] != root) {
    const Index next = m_parent[static_cast<std::size_t>(v)];
    m_parent[static_cast<std::size_t>(v)] = root;
    v = next;
  }
  return root;
}

void ImpactZones::unite(Index a, Index b) {
  for (const Index v : {a, b})
    if (m_parent[static_cast<std::size_t>(v)] < 0) m_parent[static_cast<std::size_t>(v)] = v;
  const Index ra = find(a), rb = find(b);
  // The smaller index is the root: the zones do not depend on the order of the unions.
  if (ra < rb) m_parent[static_cast<std::size_t>(rb)] = ra;
  if (rb < ra) m_parent[static_cast<std::size_t>(ra)] = rb;
}

double ImpactZones::reach_needed(const Matrix3X& x_start, const Matrix3X& x) const {
  if (m_cache_a.rows() != x.rows() || m_cache_b.rows() != x.rows())
    return std::numeric_limits<double>::infinity();
  // T_k must lie in [p_k − hi_k − r, p_k − lo_k + r] for every position p and its vertex's
  // reference box [lo, hi]: possible iff max(p − hi) − min(p − lo) ≤ 2 r.
  Eigen::Array3d most = Eigen::Array3d::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Array3d least = -most;
  for (const Index v : m_vertices) {
    const Eigen::Array3d a = vertex(m_cache_a, v).array(), b = vertex(m_cache_b, v).array();
    const Eigen::Array3d lo = a.min(b), hi = a.max(b);
    for (const Matrix3X* m : {&x_start, &x}) {
      const Eigen::Array3d p = vertex(*m, v).array();
      most = most.max(p - hi);
      least = least.min(p - lo);
    }
  }
  return std::max(0.0, 0.5 * (most - least).maxCoeff());
}

void ImpactZones::rebuild_candidates(const Matrix3X& x_start, const Matrix3X& x) {
  ++m_rebuilds;
  m_cache_a = x_start;
  m_cache_b = x;
  double edge_sum_m = 0.0;
  for (const auto& e : m_edges) edge_sum_m += (vertex(x_start, e[0]) - vertex(x_start, e[1])).norm();
  const double mean_edge_m =
      m_edges.empty() ? 0.0 : edge_sum_m / static_cast<double>(m_edges.size());
  m_cache_reach_m = reach_edges * mean_edge_m;
  // The boxes grow a little more than the reach, against rounding in the bounds.
  const double r = m_cache_reach_m * (1.0 + 1e-9) + 1e-9 * m_eta_m;
  m_cached.vt.clear();
  m_cached.ee.clear();
  std::vector<Aabb> boxes;
  boxes.reserve(m_triangles.size());
  for (const auto& t : m_triangles) boxes.push_back(swept_box(x_start, x, t.data(), 3, r + m_eta_m));
  std::vector<Index> hits;
  {
    const SpatialHash hash(zone_cell_size(boxes), std::move(boxes));
    for (const Index v : m_vertices) {
      hash.query(swept_box(x_start, x, &v, 1, r), hits);
      for (const Index t : hits) {
        const auto& tri = m_triangles[static_cast<std::size_t>(t)];
        if (tri[0] != v && tri[1] != v && tri[2] != v) m_cached.vt.push_back({v, t});
      }
    }
  }
  boxes.clear();
  for (const auto& e : m_edges) boxes.push_back(swept_box(x_start, x, e.data(), 2, r + 0.5 * m_eta_m));
  const std::vector<Aabb> edge_boxes = boxes;
  const SpatialHash hash(zone_cell_size(edge_boxes), std::move(boxes));
  for (std::size_t e = 0; e < m_edges.size(); ++e) {
    hash.query(edge_boxes[e], hits);
    const auto& a = m_edges[e];
    for (const Index f : hits) {
      if (f <= static_cast<Index>(e)) continue;
      const auto& b = m_edges[static_cast<std::size_t>(f)];
      if (a[0] != b[0] && a[0] != b[1] && a[1] != b[0] && a[1] != b[1])
        m_cached.ee.push_back({static_cast<Index>(e), f});
    }
  }
}

void ImpactZones::find_candidates(const Matrix3X& x_start, const Matrix3X& x,
                                  const std::vector<char>& changed, PairLists& out) {
  out.vt.clear();
  out.ee.clear();
  if (!m_patches && !(reach_needed(x_start, x) <= m_cache_reach_m)) rebuild_candidates(x_start, x);
  const auto moved = [&](Index v) { return changed[static_cast<std::size_t>(v)] != 0; };
  // The swept boxes of the features with a changed vertex; the others' are the last pass's.
  m_vertex_boxes.resize(static_cast<std::size_t>(x.rows()));
  for (const Index v : m_vertices)
    if (moved(v)) m_vertex_boxes[static_cast<std::size_t>(v)] = swept_box(x_start, x, &v, 1, 0.0);
  m_triangle_boxes.resize(m_triangles.size());
  for (std::size_t t = 0; t < m_triangles.size(); ++t) {
    const auto& tri = m_triangles[t];
    if (moved(tri[0]) || moved(tri[1]) || moved(tri[2]))
      m_triangle_boxes[t] = swept_box(x_start, x, tri.data(), 3, m_eta_m);
  }
  m_edge_boxes.resize(m_edges.size());
  for (std::size_t e = 0; e < m_edges.size(); ++e) {
    const auto& edge = m_edges[e];
    if (moved(edge[0]) || moved(edge[1]))
      m_edge_boxes[e] = swept_box(x_start, x, edge.data(), 2, 0.5 * m_eta_m);
  }
  if (m_patches) {
    find_patch_candidates(x_start, x, changed, out);
    return;
  }
  for (const auto& [v, t] : m_cached.vt) {
    const auto& tri = m_triangles[static_cast<std::size_t>(t)];
    if (!(moved(v) || moved(tri[0]) || moved(tri[1]) || moved(tri[2]))) continue;
    if (boxes_overlap(m_triangle_boxes[static_cast<std::size_t>(t)],
                      m_vertex_boxes[static_cast<std::size_t>(v)]))
      out.vt.push_back({v, t});
  }
  for (const auto& [e, f] : m_cached.ee) {
    const auto& a = m_edges[static_cast<std::size_t>(e)];
    const auto& b = m_edges[static_cast<std::size_t>(f)];
    if (!(moved(a[0]) || moved(a[1]) || moved(b[0]) || moved(b[1]))) continue;
    if (boxes_overlap(m_edge_boxes[static_cast<std::size_t>(e)],
                      m_edge_boxes[static_cast<std::size_t>(f)]))
      out.ee.push_back({e, f});
  }
}

// The pairs of each patch pair that the cones do not rule out (surface_patches.h): a patch
// owns each vertex and edge once and holds each triangle once, so every pair comes from one
// patch pair, once.
void ImpactZones::find_patch_candidates(const Matrix3X& x_start, const Matrix3X& x,
                                        const std::vector<char>& changed, PairLists& out) {
  const auto moved = [&](Index v) { return changed[static_cast<std::size_t>(v)] != 0; };
  // Only the patches with a changed vertex are refitted and paired: the others' fits are for
  // the same paths (paths_changed).
  const std::vector<SurfacePatch>& patches = m_patches->patches();
  m_patch_moved.resize(patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p)
    m_patch_moved[p] = std::any_of(patches[p].vertices.begin(), patches[p].vertices.end(), moved);
  m_patches->refit_swept(x_start, x, &m_patch_moved);
  m_patches->near_pairs(m_eta_m, m_culling, m_patch_pairs, &m_patch_moved);
  const auto add_vertex_triangle = [&](const SurfacePatch& a, const SurfacePatch& b) {
    const Aabb reach = inflated(b.box, m_eta_m);
    for (const Index v : a.owned_vertices) {
      const Aabb& vbox = m_vertex_boxes[static_cast<std::size_t>(v)];
      if (!boxes_overlap(vbox, reach)) continue;
      for (const Index t : b.triangles) {
        const auto& tri = m_triangles[static_cast<std::size_t>(t)];
        if (tri[0] == v || tri[1] == v || tri[2] == v) continue;
        if (!(moved(v) || moved(tri[0]) || moved(tri[1]) || moved(tri[2]))) continue;
        if (boxes_overlap(m_triangle_boxes[static_cast<std::size_t>(t)], vbox)) out.vt.push_back({v, t});
      }
    }
  };
  // The edges a patch owns whose boxes reach another patch's box (an edge box holds eta/2).
  std::vector<Index> edges_a, edges_b;
  const auto reaching = [&](const SurfacePatch& from, const SurfacePatch& to, std::vector<Index>& kept) {
    kept.clear();
    const Aabb reach = inflated(to.box, 0.5 * m_eta_m);
    for (const Index e : from.owned_edges)
      if (boxes_overlap(m_edge_boxes[static_cast<std::size_t>(e)], reach)) kept.push_back(e);
  };
  for (const auto& [p, q] : m_patch_pairs) {
    const SurfacePatch& a = (*m_patches)[p];
    const SurfacePatch& b = (*m_patches)[q];
    add_vertex_triangle(a, b);
    if (p != q) add_vertex_triangle(b, a);
    reaching(a, b, edges_a);
    if (p == q) edges_b = edges_a;
    else reaching(b, a, edges_b);
    for (std::size_t i = 0; i < edges_a.size(); ++i)
      for (std::size_t j = p == q ? i + 1 : 0; j < edges_b.size(); ++j) {
        const Index e = std::min(edges_a[i], edges_b[j]);
        const Index f = std::max(edges_a[i], edges_b[j]);
        const auto& ea = m_edges[static_cast<std::size_t>(e)];
        const auto& eb = m_edges[static_cast<std::size_t>(f)];
        if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
        if (!(moved(ea[0]) || moved(ea[1]) || moved(eb[0]) || moved(eb[1]))) continue;
        if (boxes_overlap(m_edge_boxes[static_cast<std::size_t>(e)],
                          m_edge_boxes[static_cast<std::size_t>(f)]))
          out.ee.push_back({e, f});
      }
  }
  std::sort(out.vt.begin(), out.vt.end());
  std::sort(out.ee.begin(), out.ee.end());
}

void ImpactZones::absorb(const std::vector<std::array<Index, 2>>& edges) {
  m_absorbed.insert(m_absorbed.end(), edges.begin(), edges.end());
}

void ImpactZones::collect_impacts(const Matrix3X& x_start, const Matrix3X& x,
                                  const std::vector<char>& changed,
                                  std::vector<std::array<Index, 4>>& hits) {
  hits.clear();
  const auto in_one_zone = [&](const std::array<Index, 4>& ids) {
    for (const Index v : ids)
      if (m_parent[static_cast<std::size_t>(v)] < 0) return false;
    const Index root = find(ids[0]);
    return find(ids[1]) == root && find(ids[2]) == root && find(ids[3]) == root;
  };
  const auto worth_testing = [&](const std::array<Index, 4>& ids) {
    bool any = false;
    for (const Index v : ids) any = any || changed[static_cast<std::size_t>(v)] != 0;
    return any && !in_one_zone(ids);
  };
  find_candidates(x_start, x, changed, m_candidates);
  for (const auto& [v, t] : m_candidates.vt) {
    const auto& tri = m_triangles[static_cast<std::size_t>(t)];
    const std::array<Index, 4> ids{v, tri[0], tri[1], tri[2]};
    if (!worth_testing(ids)) continue;
    ++m_tested;
    if (vertex_triangle_impact(vertex(x_start, v), vertex(x_start, tri[0]),
                               vertex(x_start, tri[1]), vertex(x_start, tri[2]), vertex(x, v),
                               vertex(x, tri[0]), vertex(x, tri[1]), vertex(x, tri[2]), m_eta_m))
      hits.push_back(ids);
  }
  for (const auto& [e, f] : m_candidates.ee) {
    const auto& a = m_edges[static_cast<std::size_t>(e)];
    const auto& b = m_edges[static_cast<std::size_t>(f)];
    const std::array<Index, 4> ids{a[0], a[1], b[0], b[1]};
    if (!worth_testing(ids)) continue;
    ++m_tested;
    if (edge_edge_impact(vertex(x_start, a[0]), vertex(x_start, a[1]), vertex(x_start, b[0]),
                         vertex(x_start, b[1]), vertex(x, a[0]), vertex(x, a[1]),
                         vertex(x, b[0]), vertex(x, b[1]), m_eta_m))
      hits.push_back(ids);
  }
}

std::vector<char> ImpactZones::paths_changed(const Matrix3X& x_start, const Matrix3X& x,
                                             bool grow) const {
  const auto n = static_cast<std::size_t>(x.rows());
  std::vector<char> changed(n, 1);
  if (grow && m_last_resolved && m_last_start.rows() == x.rows() && m_last_start == x_start)
    for (std::size_t v = 0; v < n; ++v)
      changed[v] = x.row(static_cast<Eigen::Index>(v)) != m_last_x.row(static_cast<Eigen::Index>(v));
  return changed;
}

std::vector<Index> ImpactZones::merge_zones(const std::vector<std::array<Index, 4>>& hits) {
  for (const auto& ids : hits)
    for (int k = 1; k < 4; ++k) unite(ids[0], ids[static_cast<std::size_t>(k)]);
  // Zones joined by an edge become one, so that every edge between zone vertices moves
  // rigidly (a projection that holds the zones cannot correct it).
  std::vector<Index> joined;
  for (const auto& e : m_edges) {
    if (m_parent[static_cast<std::size_t>(e[0])] < 0 || m_parent[static_cast<std::size_t>(e[1])] < 0)
      continue;
    if (find(e[0]) != find(e[1])) {
      unite(e[0], e[1]);
      joined.push_back(e[0]);
    }
  }
  return joined;
}

std::vector<std::vector<Index>> ImpactZones::touched_zones(
    const std::vector<std::array<Index, 4>>& hits, const std::vector<Index>& joined) {
  const std::size_t n = m_parent.size();
  std::vector<char> touched_root(n, 0);
  for (const auto& ids : hits) touched_root[static_cast<std::size_t>(find(ids[0]))] = 1;
  for (const Index v : joined) touched_root[static_cast<std::size_t>(find(v))] = 1;
  std::vector<std::vector<Index>> zones;
  std::vector<Index> zone_of_root(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (m_parent[v] < 0) continue;
    const auto root = static_cast<std::size_t>(find(static_cast<Index>(v)));
    if (!touched_root[root]) continue;
    if (zone_of_root[root] < 0) {
      zone_of_root[root] = static_cast<Index>(zones.size());
      zones.emplace_back();
    }
    zones[static_cast<std::size_t>(zone_of_root[root])].push_back(static_cast<Index>(v));
  }
  return zones;
}

void ImpactZones::count_zones(ImpactZoneCounts& counts) {
  const std::size_t n = m_parent.size();
  std::vector<char> is_root(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    if (m_parent[v] < 0) continue;
    m_zone_vertices.push_back(static_cast<Index>(v));
    is_root[static_cast<std::size_t>(find(static_cast<Index>(v)))] = 1;
  }
  counts.zone_vertices = static_cast<long>(m_zone_vertices.size());
  counts.zones = static_cast<int>(std::count(is_root.begin(), is_root.end(), 1));
}

ImpactZoneCounts ImpactZones::resolve(const Matrix3X& x_start, const Eigen::VectorXd& inv_mass,
                                      Matrix3X& x, bool grow) {
  ImpactZoneCounts counts;
  const auto n = static_cast<std::size_t>(x.rows());
  if (!grow) ++m_runs;
  if (!grow || m_parent.size() != n) m_parent.assign(n, -1);
  m_zone_vertices.clear();
  const Matrix3X proposed = x;
  const Eigen::VectorXd mass = impact_zone_masses(inv_mass, n);
  // Whose path changed since the last pass; with grow after a call that ended without a
  // collision in this step, since that call's end.
  std::vector<char> changed = paths_changed(x_start, x, grow);
  std::vector<std::array<Index, 4>> hits;
  // Edges absorb() gave since the last call join their zones first, as hits of a pass 0.
  std::vector<std::array<Index, 4>> absorbed;
  if (grow)
    for (const auto& e : m_absorbed) absorbed.push_back({e[0], e[1], e[1], e[1]});
  m_absorbed.clear();
  for (counts.passes = absorbed.empty() ? 1 : 0; counts.passes <= max_passes; ++counts.passes) {
    if (counts.passes == 0)
      hits = absorbed;
    else
      collect_impacts(x_start, x, changed, hits);
    if (hits.empty()) break;
    if (counts.passes > 0) counts.collisions += static_cast<long>(hits.size());
    if (counts.passes == max_passes) {
      counts.resolved = false;
      break;
    }
    const std::vector<Index> joined = merge_zones(hits);
    // The zones that gained a pair this pass move anew, rigidly, from the start.
    const std::vector<std::vector<Index>> zones = touched_zones(hits, joined);
    if (counts.passes > 0) std::fill(changed.begin(), changed.end(), 0);
    for (const auto& zone : zones) {
      apply_rigid_zone_motion(zone, x_start, proposed, mass, x);
      for (const Index v : zone) {
        if (!(inv_mass[v] > 0.0)) x.row(v) = proposed.row(v);  // pins keep their own motion
        changed[static_cast<std::size_t>(v)] = 1;
      }
    }
  }
  counts.passes = std::max(1, std::min(counts.passes, max_passes));
  m_last_start = x_start;
  m_last_x = x;
  m_last_resolved = counts.resolved;
  count_zones(counts);
  return counts;
}

}  // namespace weft::sim
