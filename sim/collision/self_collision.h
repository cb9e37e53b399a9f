#pragma once
// Self-collision response: keeps the cloth from passing through itself by
// pushing apart, position-based, every pair of mesh features closer than a contact distance:
//
//  - vertex–triangle: a vertex within `thickness_m` of a triangle it is not a corner of;
//  - edge–edge: two edges (sharing no vertex) whose closest points are within `thickness_m`;
//  - vertex–vertex "marbles" (seed 003): a sphere of radius `marble_radius_m` around each
//    vertex; two vertices closer than twice the radius are pushed apart.
//
// Neighbours are never in contact: pairs closer in the (flat) rest state than the contact
// distance plus neighbourhood_edges (by default 1) mean rest edge lengths (exclusion_radius_m),
// as seed 003 excludes marbles joined by a spring — ours join vertices up to two edges apart.
// So a flat sheet has no contacts, and the cloth can pass through itself only in a fold
// sharper than that many edges.
//
// Each contact is a one-sided distance constraint C(x) ≥ 0, projected as in position-based
// dynamics (Müller et al. 2007, "Position based dynamics"; the mass-weighted correction of
// Bridson et al. 2002, "Robust treatment of collisions, contact and friction for cloth
// animation", §7.2, without friction): Δx_k = λ w_k m_k⁻¹ ∇_k C with λ = −C / Σ w_k² m_k⁻¹, so
// momentum is conserved and pinned vertices (m⁻¹ = 0) do not move. The simulator's velocity
// update v = (x_{n+1} − x_n)/h then removes the approaching relative normal velocity.
//
// Which side: a vertex that was over a triangle (its projection inside it) at the start of the
// step is kept on the side it was on then, so a vertex that passed through the sheet within one
// step, by less than the contact distance plus the crossing depth (a quarter of the contact
// distance), is brought back; two edges whose closest points swapped sides during the step
// likewise. Faster crossings are left to the failsafe after the step's corrections
// (impact_zones.h); the per-frame intersection count (self_intersection.h) reports any left.
//
// Broad phase: the cloth's 2×2-cell patches (surface_patches.h) are refitted and paired on a
// grid of their boxes; normal cones drop flat patches and flat pairs of
// neighbouring patches (cone_culling() says how flat, by how much each is stretched); the
// remaining patch pairs give the candidate pairs within the contact distance plus a margin,
// shared out in contiguous runs among `threads` threads and then merged in order. Two
// nested Verlet lists, checked at every call relative to the cloth's common translation: the
// candidates stay valid while no pair left out can have come within the contact distance
// plus the crossing depth — surely while no vertex has moved half the margin less the
// crossing depth, else as the patches' motions tell (surface_patches.h, candidates_hold) —
// and the active pairs — the candidates within the contact distance plus a narrow band, and
// those that swapped sides within the crossing depth, which the steps project — until some
// vertex has moved half the band since they were selected. Selecting skips a candidate
// whose distance at the rebuild, less how far its vertices have moved since, keeps it out.
// Deterministic: candidates are sorted and contacts are projected in that fixed order
// (Gauss–Seidel), in up to `iterations` sweeps — after the first only over the pairs it found
// near contact — ending early when no pair is in contact.

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "base/thread_pool.h"
#include "sim/collision/surface_patches.h"
#include "sim/grid.h"
#include "sim/state_archive.h"
#include "sim/types.h"

namespace weft::sim {

struct SelfCollisionSettings {
  bool enabled = false;
  double thickness_m = 2e-3;     // vertex–triangle and edge–edge contact distance, > 0
  double marble_radius_m = 0.0;  // vertex–vertex: 0 gives thickness_m / 2
  int iterations = 4;            // Gauss–Seidel sweeps over the contacts per call, ≥ 1
  // Pairs closer at rest than the contact distance plus this many mean rest edges are never in
  // contact, 0..4. 1 (seed 003's neighbours) leaves a flat sheet without candidates but lets
  // a fold sharper than about one edge pass through itself; 0 excludes only pairs about as
  // close as the contact distance (sharing a vertex), which holds sharp folds for a larger
  // candidate list (the 64² mass-spring sphere drape ends 48 frames with 0
  // crossings instead of 4–20; bench/self_collision_bench's drop costs 1.6× as much CPU).
  double neighbourhood_edges = 1.0;
  // The failsafe after a step's corrections (impact_zones.h): continuous collision
  // detection over the step's motion and rigid impact zones, so no crossing is left. Run by
  // the step's contacts and constraints (contacts_and_constraints.h), not by SelfCollision.
  bool impact_zones = true;
  // The failsafe covers windows of steps at most this long (s), each ending at a frame's end
  // at the latest, instead of every step (Bridson et al. 2002's collision step over the
  // dynamics' substeps): explicit steps far shorter than a frame pay for it once a window.
  // The crossings a window's steps leave are taken out at its end, so no frame has one; a
  // zone's vertices leave with the zone's mean velocity over the window. 0: every step. Steps
  // of the adaptive step, of dynamic relaxation and steps that may remesh always end a window.
  double failsafe_interval_s = 1e-3;
  int threads = 0;  // threads that build the candidate list, 0..4096; 0: all hardware
                    // threads. Never changes a bit of the result.
};

// Contacts found in the first sweep of one resolve() call.
struct SelfContactCounts {
  long vertex_triangle = 0;
  long edge_edge = 0;
  long marbles = 0;
  long total() const { return vertex_triangle + edge_edge + marbles; }
};

class SelfCollision {
 public:
  // The contact features are the mesh's triangles (ClothMesh::triangles()), their edges and
  // vertices. Throws std::invalid_argument unless thickness_m is finite > 0, marble_radius_m
  // finite ≥ 0 and iterations ≥ 1 (naming the setting).
  SelfCollision(const ClothMesh& mesh, const SelfCollisionSettings& settings);

  // Pushes apart the pairs in contact at x (#V×3, m), keeping sides as they were at x_start
  // (the step's start positions). inv_mass: #V, 0 for pinned vertices. Returns the contacts of
  // the first sweep.
  SelfContactCounts resolve(const Matrix3X& x_start, const Eigen::VectorXd& inv_mass, Matrix3X& x);
  // The vertices the last resolve() moved, ascending: the only ones it can have pushed into
  // an obstacle.
  const std::vector<Index>& moved_vertices() const { return m_moved; }
  // The side memory one resolve() leaves the next, for a checkpoint: the candidate list, the
  // active pairs, the positions they were made at and the watched patch pairs (the rest is
  // recomputed from them at every call, or is scratch). restore_state() reads it into a
  // SelfCollision made for the same mesh and settings.
  void save_state(StateWriter& out) const;
  void restore_state(StateReader& in);

  double marble_radius_m() const { return m_marble_radius_m; }
  double thickness_m() const { return m_settings.thickness_m; }
  double margin_m() const { return m_margin_m; }
  // Active pairs: the candidates within the contact distance plus this band.
  double active_band_m() const { return m_band_m; }
  // Pairs that passed through each other within a step by less than the contact distance
  // plus this are brought back (a quarter of the contact distance).
  double crossing_depth_m() const {
    return 0.25 * std::max(m_settings.thickness_m, 2.0 * m_marble_radius_m);
  }
  // Pairs closer than this at rest are never in contact (marbles: 2·radius + mean rest edge).
  double exclusion_radius_m() const { return m_settings.thickness_m + m_neighbourhood_m; }
  // Candidate pairs of the current list, and how often it was rebuilt.
  std::size_t candidate_count() const {
    return m_candidates.vt.size() + m_candidates.ee.size() + m_candidates.vv.size();
  }
  long rebuilds() const { return m_rebuilds; }
  // Whether the candidate list holds vertex v against triangle t (an index into the mesh's
  // triangles), resp. edges e < f (indices into unique_edges of them).
  bool is_vertex_triangle_candidate(Index v, Index t) const;
  bool is_edge_edge_candidate(Index e, Index f) const;
  // Patch pairs the last rebuild expanded into candidates (shared among the threads).
  std::size_t patch_pair_count() const { return m_patch_pairs.size(); }
  // Wall time spent building candidate lists (broad phase) and projecting contacts (narrow).
  double broad_phase_s() const { return m_broad_s; }
  double narrow_phase_s() const { return m_narrow_s; }
  std::size_t triangle_count() const { return m_triangles.size(); }
  // When the patches' normal cones rule pairs out (surface_patches.h).
  const ConeCulling& cone_culling() const { return m_culling; }

  // Grid cells per side of a broad-phase patch (surface_patches.h).
  static constexpr Index cells_per_patch_side = 2;
  // Fewer patch pairs than this per thread are not worth a thread of their own.
  static constexpr std::size_t min_pairs_per_thread = 256;
  // Patch pairs within the contact distance plus this many margins are watched one by one
  // for a rebuild (candidates_hold); the others together.
  static constexpr double watch_margins = 2.0;
  std::size_t edge_count() const { return m_edges.size(); }

 private:
  template <class T>
  struct Lists {
    std::vector<T> vt;  // (vertex, triangle)
    std::vector<T> ee;  // (edge, edge), first < second
    std::vector<T> vv;  // (vertex, vertex), first < second
  };
  using PairLists = Lists<std::array<Index, 2>>;
  // A candidate pair and its distance when the list was built, ordered by the pair.
  struct Candidate {
    std::array<Index, 2> ids;
    double distance_m;
    bool operator<(const Candidate& other) const { return ids < other.ids; }
  };
  using CandidateLists = Lists<Candidate>;
  void measure_displacements(const Matrix3X& x);
  bool candidates_hold(const Matrix3X& x);
  void select_active(const Matrix3X& x, const Matrix3X& x_start);
  void rebuild(const Matrix3X& x);
  // One thread's share of a rebuild: the pairs it found, and its scratch.
  struct Expansion {
    CandidateLists found;
    std::vector<Index> edges_a, edges_b;
  };
  void expand(std::size_t begin, std::size_t end, const Matrix3X& x, Expansion& expansion) const;
  void add_vertex_triangle_candidates(const SurfacePatch& a, const SurfacePatch& b,
                                      const Matrix3X& x, bool rest_near,
                                      CandidateLists& out) const;
  void add_edge_edge_candidates(const SurfacePatch& a, const SurfacePatch& b, bool same,
                                const Matrix3X& x, bool rest_near, Expansion& expansion) const;
  void add_marble_candidates(const SurfacePatch& a, const SurfacePatch& b, bool same,
                             const Matrix3X& x, CandidateLists& out) const;
  bool rest_distance_below(Index v, const std::array<Index, 3>& tri, double limit_m) const;
  bool rest_distance_below(const std::array<Index, 2>& e, const std::array<Index, 2>& f,
                           double limit_m) const;
  int sweep(const PairLists& lists, const Matrix3X& x_start, const Eigen::VectorXd& inv_mass,
            Matrix3X& x, SelfContactCounts* counts, PairLists* near);
  double project_vertex_triangle(const std::array<Index, 2>& pair, const Matrix3X& x_start,
                                 const Eigen::VectorXd& inv_mass, Matrix3X& x);
  double project_edge_edge(const std::array<Index, 2>& pair, const Matrix3X& x_start,
                           const Eigen::VectorXd& inv_mass, Matrix3X& x);
  double project_marbles(const std::array<Index, 2>& pair, const Eigen::VectorXd& inv_mass,
                         Matrix3X& x);

  SelfCollisionSettings m_settings;
  double m_marble_radius_m;
  double m_margin_m;  // broad-phase margin beyond the contact distances
  double m_band_m;    // active-pair band beyond the contact distances, < m_margin_m
  double m_neighbourhood_m;  // the mean rest edge: see exclusion_radius_m()
  Matrix3X m_rest;
  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<std::array<Index, 2>> m_edges;
  std::vector<Index> m_vertices;  // the vertices of some triangle, ascending
  SurfacePatches m_patches;
  ConeCulling m_culling;
  // Rebuild scratch: the near patch pairs, triangle boxes grown by the reach, edge boxes by half.
  std::vector<std::array<Index, 2>> m_patch_pairs;
  // The patch pairs within the watch distance at the last rebuild; the patches' motions since.
  double m_watch_m = 0.0;
  std::vector<PatchPair> m_watched;
  std::vector<PatchMotion> m_motions;
  std::vector<Aabb> m_triangle_boxes, m_edge_boxes;
  std::unique_ptr<base::ThreadPool> m_pool;  // settings.threads threads, started once
  std::vector<Expansion> m_expansions;       // one per thread
  // The candidate list and the positions it was built at; the active pairs and the positions
  // they were selected at; the pairs near contact in the current call's first sweep.
  CandidateLists m_candidates;
  Matrix3X m_x_built;
  PairLists m_active;
  Matrix3X m_x_active;
  PairLists m_near;
  std::vector<Index> m_moved;  // the vertices the current call moved
  // measure_displacements: per vertex since the candidates were built, and the largest of
  // those and since the active pairs were selected.
  std::vector<double> m_moved_since_built_m;
  double m_most_moved_since_built_m = 0.0;
  double m_moved_since_active_m = 0.0;
  bool m_built = false;
  long m_rebuilds = 0;
  double m_broad_s = 0.0;
  double m_narrow_s = 0.0;
};

}  // namespace weft::sim
