// Self-collision response; the model and its limits are stated in self_collision.h.

#include "sim/collision/self_collision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "base/check.h"
#include "base/timer.h"
#include "sim/collision/proximity.h"
#include "sim/collision/self_intersection.h"

namespace weft::sim {
namespace {

// Weights within this of 0 count as on the triangle's boundary, not over its face.
constexpr double face_tolerance = 1e-9;

bool over_face(const Vec3& w) { return w.minCoeff() > face_tolerance; }

// Distance from p to triangle t of x.
double point_triangle_distance(const Matrix3X& x, Index p, const std::array<Index, 3>& t) {
  const Vec3 a = vertex(x, t[0]), b = vertex(x, t[1]), c = vertex(x, t[2]);
  const Vec3 w = closest_point_on_triangle_weights(vertex(x, p), a, b, c);
  return (vertex(x, p) - (w[0] * a + w[1] * b + w[2] * c)).norm();
}


// Which side of the plane of triangle t vertex p lies on in m: the sign of the result (its
// size is the distance times twice the area).
inline double side_of(const Matrix3X& m, Index p, const std::array<Index, 3>& t) {
  const Vec3 a = vertex(m, t[0]);
  return (vertex(m, p) - a).dot((vertex(m, t[1]) - a).cross(vertex(m, t[2]) - a));
}

// Whether vertex p is on the other side of the plane of triangle t at x than at x_start.
bool sides_swapped(const Matrix3X& x_start, const Matrix3X& x, Index p,
                   const std::array<Index, 3>& t) {
  return side_of(x, p, t) * side_of(x_start, p, t) < 0.0;
}

// Edges e and f's closest points at x: parameters s along e and u along f, and the vector d
// from the one on f to the one on e.
struct EdgeEdgeClosest {
  double s, u;
  Vec3 d;
};

inline EdgeEdgeClosest edge_edge_closest(const Matrix3X& x, const std::array<Index, 2>& e,
                                  const std::array<Index, 2>& f) {
  const Vec3 p0 = vertex(x, e[0]), p1 = vertex(x, e[1]), q0 = vertex(x, f[0]), q1 = vertex(x, f[1]);
  const auto [s, u] = closest_segment_parameters(p0, p1, q0, q1);
  return {s, u, (p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0))};
}

double edge_edge_distance(const Matrix3X& x, const std::array<Index, 2>& e,
                          const std::array<Index, 2>& f) {
  return edge_edge_closest(x, e, f).d.norm();
}

// The vector between the same material points of e and f (parameters c.s, c.u) at x_start:
// the edges' sides swapped during the step when c.d · (this) < 0.
inline Vec3 start_offset(const Matrix3X& x_start, const std::array<Index, 2>& e,
                  const std::array<Index, 2>& f, const EdgeEdgeClosest& c) {
  return (vertex(x_start, e[0]) + c.s * (vertex(x_start, e[1]) - vertex(x_start, e[0]))) -
         (vertex(x_start, f[0]) + c.u * (vertex(x_start, f[1]) - vertex(x_start, f[0])));
}

// Whether the bounding boxes of point sets a and b of x come within limit_m of each other along
// every axis: a cheap test that rules out pairs farther apart than limit_m (a gap of g along
// one axis puts every point of one set at least g from every point of the other).
template <std::size_t N, std::size_t M>
bool boxes_within(const Matrix3X& x, const std::array<Index, N>& a, const std::array<Index, M>& b,
                  double limit_m) {
  for (int k = 0; k < 3; ++k) {
    double lo_a = x(a[0], k), hi_a = lo_a, lo_b = x(b[0], k), hi_b = lo_b;
    for (std::size_t i = 1; i < N; ++i) lo_a = std::min(lo_a, x(a[i], k)), hi_a = std::max(hi_a, x(a[i], k));
    for (std::size_t i = 1; i < M; ++i) lo_b = std::min(lo_b, x(b[i], k)), hi_b = std::max(hi_b, x(b[i], k));
    if (lo_a - hi_b >= limit_m || lo_b - hi_a >= limit_m) return false;
  }
  return true;
}

bool shares_vertex(const std::array<Index, 2>& e, const std::array<Index, 2>& f) {
  return e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1];
}

// Projects one contact: constraint C = g − distance ≥ 0 along unit n, g the current gap along
// n, acting on up to four vertices with weights `w` (the gradient of g is w_k n). Returns
// whether it moved anything.
template <int N>
bool push_apart(const std::array<Index, N>& v, const std::array<double, N>& w, const Vec3& n,
                double gap_m, double distance_m, const Eigen::VectorXd& inv_mass, Matrix3X& x,
                std::vector<Index>& moved) {
  const double c = gap_m - distance_m;
  if (!(c < 0.0)) return false;
  double denominator = 0.0;
  for (int k = 0; k < N; ++k) denominator += w[k] * w[k] * inv_mass[v[k]];
  if (!(denominator > 0.0)) return false;  // every vertex involved is pinned
  const double lambda = -c / denominator;
  for (int k = 0; k < N; ++k) {
    const double step = lambda * w[k] * inv_mass[v[k]];
    if (step == 0.0) continue;
    x.row(v[k]) += step * n.transpose();
    moved.push_back(v[k]);
  }
  return true;
}

}  // namespace

SelfCollision::SelfCollision(const ClothMesh& mesh, const SelfCollisionSettings& settings)
    : m_settings(settings),
      m_rest(mesh.rest_positions),
      m_triangles(mesh.triangles()),
      m_edges(unique_edges(m_triangles)),
      m_patches(mesh, m_triangles, m_edges, cells_per_patch_side) {
  if (!(settings.thickness_m > 0.0) || !std::isfinite(settings.thickness_m))
    throw std::invalid_argument("self_collision.thickness must be finite and > 0, got " +
                                std::to_string(settings.thickness_m) + " m");
  if (!(settings.marble_radius_m >= 0.0) || !std::isfinite(settings.marble_radius_m))
    throw std::invalid_argument("self_collision.marble_radius must be finite and >= 0, got " +
                                std::to_string(settings.marble_radius_m) + " m");
  if (!(settings.neighbourhood_edges >= 0.0 && settings.neighbourhood_edges <= 4.0))
    throw std::invalid_argument("self_collision.neighbourhood must be in 0..4 edges, got " +
                                std::to_string(settings.neighbourhood_edges));
  if (settings.iterations < 1)
    throw std::invalid_argument("self_collision.iterations must be >= 1, got " +
                                std::to_string(settings.iterations));
  if (settings.threads < 0 || settings.threads > 4096)
    throw std::invalid_argument(
        "self_collision.threads must be in 0..4096 (0: all hardware threads), got " +
        std::to_string(settings.threads));
  m_pool = std::make_unique<base::ThreadPool>(settings.threads);
  m_expansions.resize(m_pool->size());
  m_moved_since_built_m.assign(static_cast<std::size_t>(m_rest.rows()), 0.0);
  m_marble_radius_m =
      settings.marble_radius_m > 0.0 ? settings.marble_radius_m : 0.5 * settings.thickness_m;
  for (const auto& t : m_triangles) m_vertices.insert(m_vertices.end(), t.begin(), t.end());
  std::sort(m_vertices.begin(), m_vertices.end());
  m_vertices.erase(std::unique(m_vertices.begin(), m_vertices.end()), m_vertices.end());
  // Neighbours: pairs closer at rest than the contact distance plus neighbourhood_edges mean
  // rest edges are never in contact, so (with the default, one edge) a flat sheet has no
  // candidates. Margin: half the mean rest edge, and
  // no less than the contact distance, plus the active band, a sixteenth of the contact
  // distance. A wider margin rebuilds less often but leaves normal-cone culling less room
  // (0.3 to 0.5 edges all cost the same at 64²); a wider band selects less often but keeps
  // more pairs active (a quarter of the contact distance cost 4 % more at 64²: measured with
  // bench/self_collision_bench).
  double edge_sum_m = 0.0;
  for (const auto& e : m_edges) edge_sum_m += (vertex(m_rest, e[0]) - vertex(m_rest, e[1])).norm();
  const double mean_edge_m = m_edges.empty() ? 0.0 : edge_sum_m / static_cast<double>(m_edges.size());
  const double contact_m = std::max(settings.thickness_m, 2.0 * m_marble_radius_m);
  m_neighbourhood_m = settings.neighbourhood_edges * mean_edge_m;
  m_band_m = contact_m / 16.0;
  m_margin_m = std::max(contact_m, 0.5 * mean_edge_m) + m_band_m;
  m_watch_m = contact_m + watch_margins * m_margin_m;
  // Normal-cone culling (surface_patches.h) drops a pair of features inside a piece of cloth
  // whose normals lie within its flat angle of an axis: they were then at least the reach
  // apart, since every pair that can be in contact is at least the smaller contact distance
  // plus the mean rest edge apart at rest (the exclusion below), and stay out of contact
  // until the next rebuild like any pair left out.
  m_culling.exclusion_m =
      std::min(settings.thickness_m, 2.0 * m_marble_radius_m) + m_neighbourhood_m;
}

// Distances between features do not change when the whole cloth translates, so what a list
// built at some reference positions has to allow for is how far each vertex's displacement
// since then differs from one common vector c: that difference, δ_v, bounds how far vertex v
// has moved relative to c, and so a pair's distance can have changed by at most the largest δ
// of one side plus that of the other. c: the centre of the displacements' bounding box, which
// makes a falling cloth rebuild only as it deforms. One pass for both lists: the largest δ
// since the active pairs were selected, and each δ since the candidates were built.
void SelfCollision::measure_displacements(const Matrix3X& x) {
  Eigen::Array3d lo_active = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Array3d hi_active = -lo_active, lo_built = lo_active, hi_built = hi_active;
  for (const Index v : m_vertices) {
    const Eigen::Array3d a = (x.row(v) - m_x_active.row(v)).transpose().array();
    const Eigen::Array3d b = (x.row(v) - m_x_built.row(v)).transpose().array();
    lo_active = lo_active.min(a);
    hi_active = hi_active.max(a);
    lo_built = lo_built.min(b);
    hi_built = hi_built.max(b);
  }
  const Eigen::RowVector3d c_active = (0.5 * (lo_active + hi_active)).matrix().transpose();
  const Eigen::RowVector3d c_built = (0.5 * (lo_built + hi_built)).matrix().transpose();
  double active2 = 0.0, built2 = 0.0;
  for (const Index v : m_vertices) {
    active2 = std::max(active2, (x.row(v) - m_x_active.row(v) - c_active).squaredNorm());
    const double d2 = (x.row(v) - m_x_built.row(v) - c_built).squaredNorm();
    built2 = std::max(built2, d2);
    m_moved_since_built_m[static_cast<std::size_t>(v)] = d2;
  }
  // Square roots in one sweep over the array, which the compiler vectorises.
  for (double& moved : m_moved_since_built_m) moved = std::sqrt(moved);
  m_moved_since_active_m = std::sqrt(active2);
  m_most_moved_since_built_m = std::sqrt(built2);
}

bool SelfCollision::is_vertex_triangle_candidate(Index v, Index t) const {
  return std::binary_search(m_candidates.vt.begin(), m_candidates.vt.end(), Candidate{{v, t}, 0.0});
}

bool SelfCollision::is_edge_edge_candidate(Index e, Index f) const {
  return std::binary_search(m_candidates.ee.begin(), m_candidates.ee.end(), Candidate{{e, f}, 0.0});
}

// Whether every pair of features left out of the candidates is still farther apart than the
// contact distance plus the crossing depth, by the patches' motions since the rebuild
// (surface_patches.h): a watched patch pair's features were at least max(gap, reach) apart
// then, and any other pair's farther than the watch distance, which bounds it by the
// patches' motions relative to the centre of all their centres.
bool SelfCollision::candidates_hold(const Matrix3X& x) {
  const base::Stopwatch watch;
  m_patches.motions(x, m_x_built, m_motions);
  const double contact_m = std::max(m_settings.thickness_m, 2.0 * m_marble_radius_m);
  const double closest_m = contact_m + crossing_depth_m();
  const double reach_m = contact_m + m_margin_m;
  bool hold = std::all_of(m_watched.begin(), m_watched.end(), [&](const PatchPair& pair) {
    const PatchMotion& a = m_motions[static_cast<std::size_t>(pair.ids[0])];
    const PatchMotion& b = m_motions[static_cast<std::size_t>(pair.ids[1])];
    return a.spread_m + b.spread_m + (a.centre - b.centre).norm() <=
           std::max(pair.gap_m, reach_m) - closest_m;
  });
  if (hold && !m_motions.empty()) {
    Vec3 lo = m_motions.front().centre, hi = lo;
    for (const PatchMotion& m : m_motions) lo = lo.cwiseMin(m.centre), hi = hi.cwiseMax(m.centre);
    const Vec3 common = 0.5 * (lo + hi);
    double farthest_m = 0.0;
    for (const PatchMotion& m : m_motions)
      farthest_m = std::max(farthest_m, m.spread_m + (m.centre - common).norm());
    hold = 2.0 * farthest_m <= m_watch_m - closest_m;
  }
  m_broad_s += watch.seconds();
  return hold;
}

// The pairs of the candidate list within the contact distance plus the active band at x: no
// other candidate can come into contact before some vertex has moved half the band. And,
// so that a pair that passed through each other within the step goes back (see the header),
// those within the contact distance plus the crossing depth whose sides have swapped since
// x_start. A candidate whose distance at the rebuild, less how far its sides can have moved
// since (measure_displacements), is farther than that is left out without looking at it.
void SelfCollision::select_active(const Matrix3X& x, const Matrix3X& x_start) {
  const base::Stopwatch watch;
  const double t = m_settings.thickness_m, band_m = active_band_m();
  const double reach_m = t + crossing_depth_m();
  const auto moved = [&](Index v) { return m_moved_since_built_m[static_cast<std::size_t>(v)]; };
  m_active.vt.clear();
  m_active.ee.clear();
  m_active.vv.clear();
  for (const Candidate& candidate : m_candidates.vt) {
    const auto& [v, k] = candidate.ids;
    const auto& tri = m_triangles[static_cast<std::size_t>(k)];
    const double moved_m = moved(v) + std::max({moved(tri[0]), moved(tri[1]), moved(tri[2])});
    if (candidate.distance_m - moved_m >= reach_m || !boxes_within(x, std::array<Index, 1>{v}, tri, reach_m))
      continue;
    const double distance_m = point_triangle_distance(x, v, tri);
    if (distance_m < t + band_m || (distance_m < reach_m && sides_swapped(x_start, x, v, tri)))
      m_active.vt.push_back(candidate.ids);
  }
  for (const Candidate& candidate : m_candidates.ee) {
    const auto& e = m_edges[static_cast<std::size_t>(candidate.ids[0])];
    const auto& f = m_edges[static_cast<std::size_t>(candidate.ids[1])];
    const double moved_m = std::max(moved(e[0]), moved(e[1])) + std::max(moved(f[0]), moved(f[1]));
    if (candidate.distance_m - moved_m >= reach_m || !boxes_within(x, e, f, reach_m)) continue;
    const EdgeEdgeClosest closest = edge_edge_closest(x, e, f);
    const double distance_m = closest.d.norm();
    if (distance_m < t + band_m ||
        (distance_m < reach_m && closest.d.dot(start_offset(x_start, e, f, closest)) < 0.0))
      m_active.ee.push_back(candidate.ids);
  }
  const double marble_m = 2.0 * m_marble_radius_m + band_m;
  for (const Candidate& candidate : m_candidates.vv) {
    const auto& [u, w] = candidate.ids;
    if (candidate.distance_m - (moved(u) + moved(w)) >= marble_m) continue;
    if ((x.row(u) - x.row(w)).squaredNorm() < marble_m * marble_m)
      m_active.vv.push_back(candidate.ids);
  }
  m_x_active = x;
  m_broad_s += watch.seconds();
}

// Candidates: pairs within contact distance + margin at x that are not neighbours; resolve()
// says when they must be rebuilt. The patches' sweep and normal cones (surface_patches.h)
// give the patch pairs to look in; each is expanded into its feature pairs, which are kept
// when a box test, the rest-state exclusion and the exact distance agree.
void SelfCollision::rebuild(const Matrix3X& x) {
  const base::Stopwatch watch;
  const double reach_m = m_settings.thickness_m + m_margin_m;
  const double marble_reach_m = 2.0 * m_marble_radius_m + m_margin_m;
  const std::size_t threads = m_expansions.size();
  // The patches' boxes and cones, and the features' boxes, a contiguous share per thread.
  const std::size_t patches = m_patches.patches().size();
  m_triangle_boxes.resize(m_triangles.size());
  m_edge_boxes.resize(m_edges.size());
  const std::size_t box_shares = std::clamp<std::size_t>(patches / 64, 1, threads);
  m_pool->run(box_shares, [&](std::size_t k) {
    m_patches.refit(x, base::share_begin(patches, box_shares, k), base::share_begin(patches, box_shares, k + 1));
    const std::size_t triangles_end = base::share_begin(m_triangles.size(), box_shares, k + 1);
    for (std::size_t t = base::share_begin(m_triangles.size(), box_shares, k); t < triangles_end; ++t) {
      const auto& tri = m_triangles[t];
      m_triangle_boxes[t] =
          inflated(bounding_box(vertex(x, tri[0]), vertex(x, tri[1]), vertex(x, tri[2])), reach_m);
    }
    const std::size_t edges_end = base::share_begin(m_edges.size(), box_shares, k + 1);
    for (std::size_t e = base::share_begin(m_edges.size(), box_shares, k); e < edges_end; ++e)
      m_edge_boxes[e] =
          inflated(bounding_box(vertex(x, m_edges[e][0]), vertex(x, m_edges[e][1])), 0.5 * reach_m);
  });
  const double patch_reach_m = std::max(reach_m, marble_reach_m);
  m_patches.pairs_within(m_watch_m, patch_reach_m, m_culling, m_watched);
  m_patch_pairs.clear();
  for (const PatchPair& pair : m_watched)
    if (!pair.culled && pair.gap_m <= patch_reach_m) m_patch_pairs.push_back(pair.ids);
  // The patch pairs in contiguous shares, one per thread, each sorting the pairs it found
  // (so that the Gauss–Seidel order follows the vertex and edge numbering); the shares are
  // then merged, so the list does not depend on the number of threads.
  const std::size_t shares =
      std::clamp<std::size_t>(m_patch_pairs.size() / min_pairs_per_thread, 1, threads);
  m_pool->run(shares, [&](std::size_t k) {
    expand(base::share_begin(m_patch_pairs.size(), shares, k),
           base::share_begin(m_patch_pairs.size(), shares, k + 1), x, m_expansions[k]);
  });
  m_candidates.vt.clear();
  m_candidates.ee.clear();
  m_candidates.vv.clear();
  const auto merge = [](const auto& share, auto& list) {
    const auto middle = static_cast<std::ptrdiff_t>(list.size());
    list.insert(list.end(), share.begin(), share.end());
    std::inplace_merge(list.begin(), list.begin() + middle, list.end());
  };
  for (std::size_t k = 0; k < shares; ++k) {
    const CandidateLists& found = m_expansions[k].found;
    merge(found.vt, m_candidates.vt);
    merge(found.ee, m_candidates.ee);
    merge(found.vv, m_candidates.vv);
  }
  m_x_built = x;
  m_built = true;
  ++m_rebuilds;
  m_broad_s += watch.seconds();
}

// The feature pairs within reach at x of patch pairs [begin, end) into expansion.found.
void SelfCollision::expand(std::size_t begin, std::size_t end, const Matrix3X& x,
                           Expansion& expansion) const {
  CandidateLists& found = expansion.found;
  found.vt.clear();
  found.ee.clear();
  found.vv.clear();
  for (std::size_t i = begin; i < end; ++i) {
    const auto [p, q] = m_patch_pairs[i];
    const SurfacePatch& a = m_patches[p];
    const SurfacePatch& b = m_patches[q];
    // Pairs of patches farther apart at rest than the exclusion radius hold no neighbours.
    const Aabb rest_a = inflated(a.rest_box, exclusion_radius_m());
    const bool rest_near = boxes_overlap(rest_a, b.rest_box);
    add_vertex_triangle_candidates(a, b, x, rest_near, found);
    if (p != q) add_vertex_triangle_candidates(b, a, x, rest_near, found);
    add_edge_edge_candidates(a, b, p == q, x, rest_near, expansion);
    add_marble_candidates(a, b, p == q, x, found);
  }
  std::sort(found.vt.begin(), found.vt.end());
  std::sort(found.ee.begin(), found.ee.end());
  std::sort(found.vv.begin(), found.vv.end());
}

// Vertices owned by patch a, those within reach of patch b's box, against b's triangles.
void SelfCollision::add_vertex_triangle_candidates(const SurfacePatch& a, const SurfacePatch& b,
                                                   const Matrix3X& x, bool rest_near,
                                                   CandidateLists& out) const {
  const double reach_m = m_settings.thickness_m + m_margin_m;
  const double exclusion_m = exclusion_radius_m();
  const Aabb target = inflated(b.box, reach_m);
  for (const Index v : a.owned_vertices) {
    const Vec3 p = vertex(x, v);
    if (!boxes_overlap(Aabb{p, p}, target)) continue;
    for (const Index k : b.triangles) {
      const auto& tri = m_triangles[static_cast<std::size_t>(k)];
      if (!boxes_overlap(Aabb{p, p}, m_triangle_boxes[static_cast<std::size_t>(k)])) continue;
      if (v == tri[0] || v == tri[1] || v == tri[2]) continue;
      if (rest_near && rest_distance_below(v, tri, exclusion_m)) continue;
      const double distance_m = point_triangle_distance(x, v, tri);
      if (distance_m < reach_m) out.vt.push_back({{v, k}, distance_m});
    }
  }
}

// Edges owned by patch a against those owned by patch b (each unordered pair once): first
// the edges of each whose box reaches the other patch's box.
void SelfCollision::add_edge_edge_candidates(const SurfacePatch& a, const SurfacePatch& b,
                                             bool same, const Matrix3X& x, bool rest_near,
                                             Expansion& expansion) const {
  const double reach_m = m_settings.thickness_m + m_margin_m;
  const double exclusion_m = exclusion_radius_m();
  const auto reaching = [&](const SurfacePatch& from, const SurfacePatch& to,
                            std::vector<Index>& out) {
    out.clear();
    const Aabb target = inflated(to.box, 0.5 * reach_m);
    for (const Index e : from.owned_edges)
      if (boxes_overlap(m_edge_boxes[static_cast<std::size_t>(e)], target)) out.push_back(e);
  };
  std::vector<Index>& edges_a = expansion.edges_a;
  std::vector<Index>& edges_b = expansion.edges_b;
  reaching(a, b, edges_a);
  if (same) edges_b = edges_a;
  else reaching(b, a, edges_b);
  for (std::size_t i = 0; i < edges_a.size(); ++i) {
    for (std::size_t j = same ? i + 1 : 0; j < edges_b.size(); ++j) {
      const Index ei = std::min(edges_a[i], edges_b[j]);
      const Index ej = std::max(edges_a[i], edges_b[j]);
      const auto& e = m_edges[static_cast<std::size_t>(ei)];
      const auto& f = m_edges[static_cast<std::size_t>(ej)];
      if (!boxes_overlap(m_edge_boxes[static_cast<std::size_t>(ei)],
                         m_edge_boxes[static_cast<std::size_t>(ej)]) ||
          shares_vertex(e, f))
        continue;
      if (rest_near && rest_distance_below(e, f, exclusion_m)) continue;
      const double distance_m = edge_edge_distance(x, e, f);
      if (distance_m < reach_m) expansion.found.ee.push_back({{ei, ej}, distance_m});
    }
  }
}

// Vertices owned by patch a against those owned by patch b (each unordered pair once).
void SelfCollision::add_marble_candidates(const SurfacePatch& a, const SurfacePatch& b, bool same,
                                          const Matrix3X& x, CandidateLists& out) const {
  const double marble_contact_m = 2.0 * m_marble_radius_m;
  const double reach2 = std::pow(marble_contact_m + m_margin_m, 2);
  const double exclusion2 = std::pow(marble_contact_m + m_neighbourhood_m, 2);
  for (std::size_t i = 0; i < a.owned_vertices.size(); ++i) {
    for (std::size_t j = same ? i + 1 : 0; j < b.owned_vertices.size(); ++j) {
      const Index u = std::min(a.owned_vertices[i], b.owned_vertices[j]);
      const Index w = std::max(a.owned_vertices[i], b.owned_vertices[j]);
      const double distance2 = (x.row(u) - x.row(w)).squaredNorm();
      if (distance2 < reach2 && (m_rest.row(u) - m_rest.row(w)).squaredNorm() >= exclusion2)
        out.vv.push_back({{u, w}, std::sqrt(distance2)});
    }
  }
}

// Whether the rest distance between the features is below limit_m. A corner (endpoint)
// distance bounds it from above, which settles the neighbours without the exact distance.
bool SelfCollision::rest_distance_below(Index v, const std::array<Index, 3>& tri,
                                        double limit_m) const {
  const double limit2 = limit_m * limit_m;
  for (const Index c : tri)
    if ((m_rest.row(v) - m_rest.row(c)).squaredNorm() < limit2) return true;
  return point_triangle_distance(m_rest, v, tri) < limit_m;
}

bool SelfCollision::rest_distance_below(const std::array<Index, 2>& e,
                                        const std::array<Index, 2>& f, double limit_m) const {
  const double limit2 = limit_m * limit_m;
  for (const Index p : e)
    for (const Index q : f)
      if ((m_rest.row(p) - m_rest.row(q)).squaredNorm() < limit2) return true;
  return edge_edge_distance(m_rest, e, f) < limit_m;
}

// Each contact kind: the pair's gap along its contact normal (side-aware, see the header),
// after pushing the pair apart if it was below the contact distance. A pair whose normal is
// undefined (degenerate triangle, coincident points) has an infinite gap.
double SelfCollision::project_vertex_triangle(const std::array<Index, 2>& pair,
                                              const Matrix3X& x_start,
                                              const Eigen::VectorXd& inv_mass, Matrix3X& x) {
  constexpr double none = std::numeric_limits<double>::infinity();
  const double t = m_settings.thickness_m;
  const Index v = pair[0];
  const auto& tri = m_triangles[static_cast<std::size_t>(pair[1])];
  const Vec3 p = vertex(x, v), a = vertex(x, tri[0]), b = vertex(x, tri[1]), c = vertex(x, tri[2]);
  const Vec3 w = closest_point_on_triangle_weights(p, a, b, c);
  const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
  Vec3 n;
  double gap_m;
  if (over_face(w)) {
    const Vec3 normal = (b - a).cross(c - a);
    if (!(normal.squaredNorm() > 0.0)) return none;
    n = normal.normalized();
    // The side it was on when over the face at the start of the step; else where it is now.
    const double side0 = side_of(x_start, v, tri);
    const double side_now = (p - q).dot(n);
    // Whether it was over the face matters only when the two sides differ.
    const bool same_side = side0 == 0.0 || (side_now != 0.0 && (side0 > 0.0) == (side_now > 0.0));
    const bool was_over =
        !same_side &&
        over_face(closest_point_on_triangle_weights(vertex(x_start, v), vertex(x_start, tri[0]),
                                                    vertex(x_start, tri[1]), vertex(x_start, tri[2])));
    const double side = was_over ? side0 : side_now;
    if (side < 0.0) n = -n;
    gap_m = (p - q).dot(n);
  } else {
    gap_m = (p - q).norm();
    if (!(gap_m > 0.0)) return none;
    n = (p - q) / gap_m;
  }
  push_apart<4>({v, tri[0], tri[1], tri[2]}, {1.0, -w[0], -w[1], -w[2]}, n, gap_m, t, inv_mass, x, m_moved);
  return gap_m;
}

double SelfCollision::project_edge_edge(const std::array<Index, 2>& pair, const Matrix3X& x_start,
                                        const Eigen::VectorXd& inv_mass, Matrix3X& x) {
  constexpr double none = std::numeric_limits<double>::infinity();
  const auto& e = m_edges[static_cast<std::size_t>(pair[0])];
  const auto& f = m_edges[static_cast<std::size_t>(pair[1])];
  const EdgeEdgeClosest closest = edge_edge_closest(x, e, f);
  const auto& [s, u, d] = closest;
  // If the closest points swapped sides since the start of the step, the edges passed
  // through each other and go back to the start side.
  const bool interior = s > 0.0 && s < 1.0 && u > 0.0 && u < 1.0;
  const Vec3 d0 = interior ? start_offset(x_start, e, f, closest) : Vec3::Zero();
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
                m_settings.thickness_m, inv_mass, x, m_moved);
  return gap_m;
}

double SelfCollision::project_marbles(const std::array<Index, 2>& pair,
                                      const Eigen::VectorXd& inv_mass, Matrix3X& x) {
  const Vec3 d = vertex(x, pair[0]) - vertex(x, pair[1]);
  const double length = d.norm();
  if (!(length > 0.0)) return std::numeric_limits<double>::infinity();
  push_apart<2>(pair, {1.0, -1.0}, d / length, length, 2.0 * m_marble_radius_m, inv_mass, x,
                m_moved);
  return length;
}

// One Gauss–Seidel sweep over `lists`; returns how many pairs were in contact. `near`, when
// given, collects the pairs within twice the contact distance: the later sweeps of the same
// call visit only those (a pair farther away is not reached by a few sweeps' small pushes; the
// next step's first sweep sees every candidate again).
int SelfCollision::sweep(const PairLists& lists, const Matrix3X& x_start,
                         const Eigen::VectorXd& inv_mass, Matrix3X& x, SelfContactCounts* counts,
                         PairLists* near) {
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
  WEFT_CHECK(x_start.rows() == x.rows() && inv_mass.size() == x.rows() &&
                 x.rows() == m_rest.rows(),
             "SelfCollision::resolve: " + std::to_string(x.rows()) + " positions, " +
                 std::to_string(x_start.rows()) + " start positions and " +
                 std::to_string(inv_mass.size()) + " inverse masses for a mesh of " +
                 std::to_string(m_rest.rows()) + " vertices");
  SelfContactCounts counts;
  // Two Verlet lists, checked at every call: the candidates within the margin, rebuilt when
  // a pair left out may have come within the contact distance plus the crossing depth, so
  // that every such pair is a candidate — surely not while no vertex has moved (margin −
  // crossing depth)/2, and else as candidates_hold() tells patch pair by patch pair; and the
  // active pairs, reselected from the candidates when some vertex has moved half the band.
  if (m_built) {
    const base::Stopwatch check_watch;
    measure_displacements(x);
    m_broad_s += check_watch.seconds();
  }
  if (!m_built || (m_most_moved_since_built_m > 0.5 * (m_margin_m - crossing_depth_m()) &&
                   !candidates_hold(x))) {
    rebuild(x);
    std::fill(m_moved_since_built_m.begin(), m_moved_since_built_m.end(), 0.0);
    select_active(x, x_start);
  } else if (m_moved_since_active_m > 0.5 * active_band_m()) {
    select_active(x, x_start);
  }
  const base::Stopwatch watch;
  m_moved.clear();
  m_near.vt.clear();
  m_near.ee.clear();
  m_near.vv.clear();
  int contacts = sweep(m_active, x_start, inv_mass, x, &counts, &m_near);
  for (int i = 1; i < m_settings.iterations && contacts > 0; ++i)
    contacts = sweep(m_near, x_start, inv_mass, x, nullptr, nullptr);
  std::sort(m_moved.begin(), m_moved.end());
  m_moved.erase(std::unique(m_moved.begin(), m_moved.end()), m_moved.end());
  m_narrow_s += watch.seconds();
  return counts;
}

void SelfCollision::save_state(StateWriter& out) const {
  out.section("self-collision");
  out.pod(m_built);
  out.pod(m_rebuilds);
  for (const auto* list : {&m_candidates.vt, &m_candidates.ee, &m_candidates.vv}) out.pods(*list);
  out.matrix(m_x_built);
  for (const auto* list : {&m_active.vt, &m_active.ee, &m_active.vv}) out.pods(*list);
  out.matrix(m_x_active);
  out.pods(m_watched);
}

void SelfCollision::restore_state(StateReader& in) {
  in.section("self-collision");
  in.pod(m_built);
  in.pod(m_rebuilds);
  const Eigen::Index n = m_built ? m_rest.rows() : -1;
  for (auto* list : {&m_candidates.vt, &m_candidates.ee, &m_candidates.vv}) in.pods(*list);
  in.matrix(m_x_built, n, 3);
  for (auto* list : {&m_active.vt, &m_active.ee, &m_active.vv}) in.pods(*list);
  in.matrix(m_x_active, n, 3);
  in.pods(m_watched);
  const auto bad = [](Index id, std::size_t size) { return id < 0 || static_cast<std::size_t>(id) >= size; };
  for (const PatchPair& pair : m_watched)
    if (bad(pair.ids[0], m_patches.patches().size()) || bad(pair.ids[1], m_patches.patches().size()))
      in.fail("a patch pair outside the mesh's patches");
  const auto ids_of = [](const auto& entry) -> const std::array<Index, 2>& {
    if constexpr (std::is_same_v<std::decay_t<decltype(entry)>, std::array<Index, 2>>)
      return entry;
    else
      return entry.ids;
  };
  const auto check = [&](const auto& list, std::size_t first, std::size_t second) {
    for (const auto& entry : list) {
      const std::array<Index, 2>& ids = ids_of(entry);
      if (bad(ids[0], first) || bad(ids[1], second)) in.fail("a contact pair outside the mesh");
    }
  };
  const std::size_t v = static_cast<std::size_t>(m_rest.rows());
  check(m_candidates.vt, v, m_triangles.size());
  check(m_candidates.ee, m_edges.size(), m_edges.size());
  check(m_candidates.vv, v, v);
  check(m_active.vt, v, m_triangles.size());
  check(m_active.ee, m_edges.size(), m_edges.size());
  check(m_active.vv, v, v);
}

}  // namespace weft::sim
