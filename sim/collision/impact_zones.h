#pragma once
// The failsafe of self-collision (issue 23): rigid impact zones (Provot 1997; Bridson et al.
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
// Broad phase: a spatial hash (spatial_hash.h) of the triangles' and of the edges' boxes swept
// over the step and grown by eta; after the first pass only the pairs touching a vertex whose
// path changed are tested again. Single-threaded, fixed order: the same bits every time.

#include <array>
#include <vector>

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

  // Replaces the motion of the colliding zones (rule above). inv_mass: #V, 0 at pins. grow:
  // keep the zones of the last call (same step, x moved since only outside them) and let them
  // grow, instead of starting without zones.
  ImpactZoneCounts resolve(const Matrix3X& x_start, const Eigen::VectorXd& inv_mass, Matrix3X& x,
                           bool grow = false);

  // The vertices in some zone after the last resolve(), ascending (with grow, the earlier
  // calls' zones too).
  const std::vector<Index>& zone_vertices() const { return m_zone_vertices; }
  double eta_m() const { return m_eta_m; }

  static constexpr int max_passes = 200;

 private:
  struct PairLists {
    std::vector<std::array<Index, 2>> vt;  // (vertex, triangle)
    std::vector<std::array<Index, 2>> ee;  // (edge, edge), first < second
  };
  void find_candidates(const Matrix3X& x_start, const Matrix3X& x, PairLists& out) const;
  Index find(Index v);
  void unite(Index a, Index b);

  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<std::array<Index, 2>> m_edges;
  std::vector<Index> m_vertices;  // the vertices of some triangle, ascending
  double m_eta_m;
  std::vector<Index> m_parent;  // union–find over vertices; −1: in no zone
  std::vector<Index> m_zone_vertices;
};

}  // namespace weft::sim
