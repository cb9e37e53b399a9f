#pragma once
// Self-collision broad phase on patches of the cloth. The triangles are
// grouped into square patches of the warp/weft grid (cells_per_side² cells each); every
// vertex and every edge is owned by exactly one patch (the patch of the first triangle that
// has it). Each rebuild gives a patch its bounding box and its normal cone — the axis of its
// summed area-weighted normals and the largest angle between that axis and a triangle's
// normal — then finds the patch pairs that can hold a contact, those whose grown boxes overlap
// (box_pairs.h), and drops the pairs the normal cones rule out:
//
//  - a patch whose cone is narrower than its flat angle (ConeCulling) cannot come near
//    itself, and
//  - neither can two neighbouring patches (sharing a side or a corner) when the union of the
//    patches in the square or strip of the patch grid that holds both is — all of them
//    present, so that the union is a convex piece of the grid —
//
// (Volino & Magnenat-Thalmann 1994, "Efficient self-collision detection on smoothly
// discretized surface animations using geometrical shape regularity"; Provot 1997). The
// reason, and when it holds: over a connected surface whose normals all lie within θ of an
// axis a, the surface is a height field over the plane ⊥ a with slope at most tan θ, so two
// of its points a geodesic distance g apart (along the surface) are at least g·cos θ apart in
// space — when the patch's projection is convex, as a square of cloth that is not folded
// over is. And the geodesic distance is at least the rest distance times the least stretch
// of the triangles, measured at each refit, so the bound holds however much the cloth is
// compressed or sheared (ConeCulling). The contour test of Volino & Magnenat-Thalmann, which
// also rules out a patch that winds like a spiral ramp, is not done: such a patch would need
// a half turn within a few cells.
//
// On a mesh without a grid (a triangle mesh from a file) a patch is the triangles whose
// centroids fall in one square of the material coordinates (cells_per_side mean edge lengths
// a side), and nothing is culled by the normal cones: such a patch need not be convex or even
// connected, which the argument above needs.
//
// Every vertex–triangle, edge–edge and vertex–vertex pair of features lies in exactly one
// returned patch pair (by ownership), so a caller that expands the pairs sees each feature
// pair at most once. Deterministic.

#include <array>
#include <vector>

#include "base/constants.h"
#include "sim/collision/box_pairs.h"
#include "sim/collision/spatial_hash.h"
#include "sim/grid.h"
#include "sim/types.h"

namespace weft::sim {

struct SurfacePatch {
  std::array<Index, 2> grid{0, 0};     // patch coordinates along warp and weft
  std::vector<Index> triangles;        // indices into the triangle list
  std::vector<Index> owned_vertices;   // ascending
  std::vector<Index> owned_edges;      // indices into the edge list, ascending
  Aabb rest_box;                       // of its triangles in the rest state
  // Set by SurfacePatches::refit: the box of its triangles at x, and the normal cone.
  Aabb box;
  Vec3 normal_sum = Vec3::Zero();      // Σ of the triangles' area-weighted normals
  double cone_angle_rad = 0.0;         // π when undefined (a degenerate triangle)
  // The least stretch of its triangles: the smallest singular value of their deformation
  // gradients, so that no curve on the patch is shorter than this times its rest length.
  double least_stretch = 1.0;
  std::vector<Index> vertices;         // of its triangles (owned or not), ascending
};

// Two patches within some distance of each other (SurfacePatches::pairs_within).
struct PatchPair {
  std::array<Index, 2> ids{0, 0};  // first ≤ second
  double gap_m = 0.0;   // largest separation of their boxes along an axis: no point of one is
                        // nearer than this to a point of the other
  bool culled = false;  // within reach, and the normal cones rule out contact
};

// A patch's displacement since reference positions: the centre of the box of its vertices'
// displacements, and the largest deviation of one of them from it (the spread). Two points
// of patches p and q have changed their distance by at most spread_p + spread_q +
// |centre_p − centre_q|: small for a piece of cloth that swings or falls as a whole, however
// fast, growing only with how the two patches move relative to each other.
struct PatchMotion {
  Vec3 centre = Vec3::Zero();
  double spread_m = 0.0;
};

// When the normal cones rule pairs out. Points of a piece of cloth whose normals lie within θ
// of an axis and whose least stretch is s are at least s·cos θ times their rest distance
// apart; the pairs that can be in contact are at least exclusion_m apart at rest, so none
// of them comes within the reach while s·cos θ·exclusion ≥ reach. The flat angle of a piece
// of cloth is then min(max_angle, acos(reach / (s·exclusion))), and 0 — nothing ruled out —
// when that has no solution or exclusion_m is 0.
struct ConeCulling {
  double exclusion_m = 0.0;
  double max_angle_rad = 60.0 * base::kPi / 180.0;
  double flat_angle_rad(double reach_m, double least_stretch) const;
};

class SurfacePatches {
 public:
  // triangles: ClothMesh::triangles(); edges: unique_edges(triangles). A patch covers
  // cells_per_side × cells_per_side grid cells (≥ 1). Throws std::invalid_argument if
  // cells_per_side < 1 or the triangles do not come from the mesh's kept cells.
  SurfacePatches(const ClothMesh& mesh, const std::vector<std::array<Index, 3>>& triangles,
                 const std::vector<std::array<Index, 2>>& edges, Index cells_per_side);

  // Boxes, normal cones and least stretches at positions x (#V×3, m).
  void refit(const Matrix3X& x);
  // The same for patches [first, end) only; calls for disjoint ranges may run at once.
  void refit(const Matrix3X& x, std::size_t first, std::size_t end);
  // The same over a step, every vertex moving on its straight path from x_start to x: each
  // box holds the patch's triangles at both ends (so all along the paths), each cone every
  // normal its triangles take on the way, and least_stretch bounds every triangle's least
  // stretch along the way from below. For continuous collision (impact_zones.h).
  // With `only` (one flag per patch), the flagged patches alone; the others keep their fit.
  void refit_swept(const Matrix3X& x_start, const Matrix3X& x,
                   const std::vector<char>* only = nullptr);

  // The patch pairs (first ≤ second; (p, p) is a patch against itself) whose boxes come
  // within reach_m of each other and that the normal cones do not rule out (`culling`; a
  // default ConeCulling rules out nothing). Sorted. Call refit first. With `wanted` (one flag
  // per patch), only the pairs with a wanted patch.
  void near_pairs(double reach_m, const ConeCulling& culling,
                  std::vector<std::array<Index, 2>>& pairs,
                  const std::vector<char>* wanted = nullptr);
  // Every patch pair whose boxes are at most watch_m apart along each axis (a pair left out
  // is farther apart than watch_m), with its gap; those within reach_m (≤ watch_m) that the
  // cones rule out, as near_pairs() drops them, are marked culled. Sorted. `wanted` as for
  // near_pairs.
  void pairs_within(double watch_m, double reach_m, const ConeCulling& culling,
                    std::vector<PatchPair>& pairs, const std::vector<char>* wanted = nullptr);

  // Each patch's motion from `reference` to x (both #V×3), one per patch.
  void motions(const Matrix3X& x, const Matrix3X& reference,
               std::vector<PatchMotion>& motions) const;

  const std::vector<SurfacePatch>& patches() const { return m_patches; }
  const SurfacePatch& operator[](Index p) const { return m_patches[static_cast<std::size_t>(p)]; }
  // Whether patches p ≠ q share a grid side or corner.
  bool neighbours(Index p, Index q) const;
  // Whether every normal of the union of the patches in the grid rectangle spanned by
  // neighbours p and q lies within the union's flat angle of its axis, given each patch's
  // flat angle (the union's is the least of its members'). False when one of them is missing
  // (cut away, as at a disc's edge) or a cone is undefined.
  bool union_flat(Index p, Index q, const std::vector<double>& flat_angles_rad) const;

 private:
  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<SurfacePatch> m_patches;
  Index m_patches_u = 0;              // patch grid columns
  std::vector<Index> m_patch_of_grid; // patch at grid (i, j): [j · m_patches_u + i], −1 if none
  bool m_cone_culling = true;         // false on a mesh without a grid (see the top)
  void set_cone(SurfacePatch& patch, bool degenerate, int normals_per_triangle);
  // Scratch: each triangle's area-weighted normal (refit), or its three control normals over
  // the step (refit_swept).
  std::vector<Vec3> m_normals;
  // Per triangle: the inverse of its rest edge matrix in a frame of its own plane, for the
  // deformation gradient F = [x1 − x0, x2 − x0] · m_rest_inverse (3×2).
  std::vector<Eigen::Matrix2d> m_rest_inverse;
  // pairs_within's scratch: the grown boxes, their overlapping pairs, the flat angles.
  BoxPairs m_box_pairs;
  std::vector<Aabb> m_grown_boxes;
  std::vector<std::array<Index, 2>> m_overlaps;
  std::vector<double> m_flat_angles_rad;
  std::vector<PatchPair> m_within;  // near_pairs'
};

}  // namespace weft::sim
