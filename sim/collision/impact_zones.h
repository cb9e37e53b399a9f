#pragma once
// The failsafe of self-collision: rigid impact zones (Provot 1997; Bridson et al.
// 2002, "Robust treatment of collisions, contact and friction for cloth animation", §7.4),
// which leave no crossing that the step's start did not have, whatever the step's motion.
//
// After a step's push-outs and projections have moved the cloth from x_start to x, every
// vertex–triangle and edge–edge pair (not sharing a vertex) is tested by continuous collision
// detection over the straight paths x_start → x (continuous_collision.h, thickness eta). The
// vertices of each colliding pair are merged into an impact zone (union–find; zones merge when
// they share a vertex), and each zone's motion is replaced by the rigid motion that keeps the
// zone's linear momentum and, to first order in the rotation, its angular momentum about its
// centre of mass: x_i ← c_1 + R (x_start_i − c_0), with c_0, c_1 the centres of mass of the
// zone at the start and at the proposed end and R the rotation by ω = I⁻¹ L (L and I the
// angular momentum of the proposed displacements and the inertia tensor, both about c_0 at the
// start). Zones joined by a mesh edge are merged, so every edge between zone vertices keeps its
// length. Then the paths are tested again, until no pair collides. A rigid motion keeps every
// distance inside a zone, so the zone cannot pass through itself and its edges keep their start
// lengths; pairs with all vertices in one zone are not tested. If every zone grew into the whole
// cloth, it would move rigidly from its start, which had no crossing: the loop ends. Pinned
// vertices (inverse mass 0) weigh a million times the heaviest vertex and keep their own end
// positions.
//
// Broad phase: the pairs whose boxes swept over the step (triangles grown by eta, edges by
// eta/2) overlap; after the first pass only the pairs touching a vertex whose path changed are
// tested again, and a call with `grow` tests at first only the pairs touching a vertex moved
// since the last call (the others were tested at those positions).
//
// On a warp/weft grid the pairs come from the grid's patches (surface_patches.h), refitted over
// the step at every pass (refit_swept: boxes, normal cones and least stretches that hold all
// along the straight paths), and a patch or two neighbouring ones flat all along the step are
// ruled out: on a flat grid two features sharing no vertex are at rest at least the least
// altitude of a triangle apart, and the cones' bound keeps them farther than eta.
//
// On a mesh without a grid the pairs are filtered from
// a cached list (a Verlet list) of the pairs whose reference boxes — each vertex's box from A_i
// to B_i, the start and end positions at the list's build — overlap when grown by a reach r
// more. The list holds every pair whose swept boxes overlap while some common translation T
// brings each start and end position within r (per coordinate) of its vertex's reference box
// plus T: each swept box then lies inside its feature's reference box plus T grown by r. That
// is checked at every pass (the smallest such reach is a max/min per coordinate), and the list
// is rebuilt from the current step when it fails, with a spatial hash (spatial_hash.h). So the
// pairs tested, and the results, are those of a search from scratch at every pass; the list
// only saves time: the passes and the projections with the zones held within a step (the
// reach covers their corrections), and steps whose motion stays within the reach (the search
// from scratch took ~35 ms per pass at 64²). Single-threaded, fixed order: the
// same bits every time.

#include <array>
#include <memory>
#include <vector>

#include "sim/collision/spatial_hash.h"
#include "sim/collision/surface_patches.h"
#include "sim/grid.h"
#include "sim/types.h"

namespace weft::sim {

struct ImpactZoneCounts {
  int passes = 0;             // detection passes (1 when nothing collided)
  long collisions = 0;        // colliding pairs found, over all passes
  long zone_vertices = 0;     // vertices in some zone at the end
  int zones = 0;              // zones at the end
  bool resolved = true;       // false: the pass limit was hit with collisions left
};

// The rigid motion of a set of vertices (zone) from x_start that replaces their proposed motion
// to x_proposed (rule above), written into x for those vertices (x may be x_proposed). mass: #V
// masses (kg), > 0 for every zone vertex.
void apply_rigid_zone_motion(const std::vector<Index>& zone, const Matrix3X& x_start,
                             const Matrix3X& x_proposed, const Eigen::VectorXd& mass, Matrix3X& x);

class ImpactZones {
 public:
  // triangles: the cloth's triangles; their edges are the edge features. eta_m > 0: the
  // continuous-collision thickness.
  ImpactZones(std::vector<std::array<Index, 3>> triangles, double eta_m);
  // The same over a cloth mesh's triangles (ClothMesh::triangles()). On a warp/weft grid the
  // pairs are found on patches of the grid whose normal cones over the step rule out the
  // flat ones (rule above), instead of the cached list.
  ImpactZones(const ClothMesh& mesh, double eta_m);
  ~ImpactZones();

  // Replaces the motion of the colliding zones (rule above). inv_mass: #V, 0 at pins. grow:
  // keep the zones of the last call (same step, x moved since only outside them) and let them
  // grow, instead of starting without zones.
  ImpactZoneCounts resolve(const Matrix3X& x_start, const Eigen::VectorXd& inv_mass, Matrix3X& x,
                           bool grow = false);

  // Edges (pairs of vertices) whose two ends the next resolve() with grow puts into one zone,
  // moved rigidly like a colliding pair's: edges leaving a zone that a projection with the
  // zones held could not bring within its tolerance (the zone takes in their free ends).
  void absorb(const std::vector<std::array<Index, 2>>& edges);

  // The vertices in some zone after the last resolve(), ascending (with grow, the earlier
  // calls' zones too).
  const std::vector<Index>& zone_vertices() const { return m_zone_vertices; }
  double eta_m() const { return m_eta_m; }

  static constexpr int max_passes = 200;
  // The cached list's reach r, in mean edge lengths (of the step it was built from).
  static constexpr double reach_edges = 0.25;
  // Grid cells per side of a patch, on a grid.
  static constexpr Index patch_cells_per_side = 2;
  // Times the cached candidate list was built.
  long candidate_rebuilds() const { return m_rebuilds; }
  // Pairs tested by continuous collision detection, over all calls.
  long tested_pairs() const { return m_tested; }
  // Calls of resolve() without grow: the failsafe's runs.
  long runs() const { return m_runs; }

 private:
  struct PairLists {
    std::vector<std::array<Index, 2>> vt;  // (vertex, triangle)
    std::vector<std::array<Index, 2>> ee;  // (edge, edge), first < second
  };
  // The pairs (sharing no vertex) whose swept boxes overlap and that touch a vertex v with
  // changed[v] != 0, vt ascending by (vertex, triangle) and ee by (edge, edge).
  void find_candidates(const Matrix3X& x_start, const Matrix3X& x,
                       const std::vector<char>& changed, PairLists& out);
  // The smallest reach for which the cached list holds (rule above); infinite without a list.
  double reach_needed(const Matrix3X& x_start, const Matrix3X& x) const;
  void rebuild_candidates(const Matrix3X& x_start, const Matrix3X& x);
  // find_candidates on the grid's patches (m_patches).
  void find_patch_candidates(const Matrix3X& x_start, const Matrix3X& x,
                             const std::vector<char>& changed, PairLists& out);
  // The candidate pairs that touch a changed vertex, are not inside one zone already and
  // collide over the step from x_start to x (continuous_collision.h), in the candidates' order.
  void collect_impacts(const Matrix3X& x_start, const Matrix3X& x,
                       const std::vector<char>& changed, std::vector<std::array<Index, 4>>& hits);
  Index find(Index v);
  void unite(Index a, Index b);
  // resolve()'s phases. Per vertex of x, whether its path may differ from the last call's
  // (all do unless grow follows a call that ended without a collision from the same x_start).
  std::vector<char> paths_changed(const Matrix3X& x_start, const Matrix3X& x, bool grow) const;
  // Unites the vertices of each hit, then the zones a mesh edge joins; returns one end of each
  // such edge.
  std::vector<Index> merge_zones(const std::vector<std::array<Index, 4>>& hits);
  // The vertices of each zone holding a hit or a joined vertex, ascending, the zones in the
  // order of their first vertex.
  std::vector<std::vector<Index>> touched_zones(const std::vector<std::array<Index, 4>>& hits,
                                                const std::vector<Index>& joined);
  // Lists the zones' vertices (m_zone_vertices) and counts them and the zones.
  void count_zones(ImpactZoneCounts& counts);

  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<std::array<Index, 2>> m_edges;
  std::vector<Index> m_vertices;  // the vertices of some triangle, ascending
  double m_eta_m;
  std::vector<Index> m_parent;  // union–find over vertices; −1: in no zone
  std::vector<Index> m_zone_vertices;
  std::vector<std::array<Index, 2>> m_absorbed;  // for the next resolve() with grow
  // The last resolve()'s positions and whether it ended without a collision: a call with grow
  // need not test again the pairs that did not move since.
  Matrix3X m_last_start, m_last_x;
  bool m_last_resolved = false;
  // The cached candidate list (ordered as find_candidates' answer), its reference boxes' ends
  // A, B and reach r (rule above).
  PairLists m_cached;
  PairLists m_candidates;  // collect_impacts' workspace
  Matrix3X m_cache_a, m_cache_b;
  double m_cache_reach_m = 0.0;
  long m_rebuilds = 0;
  long m_tested = 0;
  long m_runs = 0;
  std::vector<Aabb> m_triangle_boxes, m_edge_boxes, m_vertex_boxes;  // swept; scratch
  // On a grid: its patches, and when their cones rule pairs out (exclusion: the least
  // altitude of a rest triangle, below which no two features sharing no vertex come at rest).
  std::unique_ptr<SurfacePatches> m_patches;
  ConeCulling m_culling;
  std::vector<std::array<Index, 2>> m_patch_pairs;  // scratch
  std::vector<char> m_patch_moved;                   // scratch: per patch, a changed vertex
};

}  // namespace weft::sim
