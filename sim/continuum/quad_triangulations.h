#pragma once
// The two ways to split the cloth's warp/weft quads into triangles, for the continuum terms.
//
// A term built on one split — every quad cut along the same diagonal — is not symmetric: a
// dihedral hinge's stencil is skewed along its edge, and on a free edge of the cloth the skews
// no longer cancel between neighbouring hinges, so bending along the warp puts a twisting
// couple on the edge. On the Peirce cantilever strip that made the tip drop 56 % too large and
// drift away under refinement. Built on both splits at half weight each, the skews cancel
// exactly (a sheet bent along one direction gets the forces of a symmetric three-point
// stencil) and uniform strains keep their energies. Rendering still uses ClothMesh::triangles().
//
// A mesh without a grid (a triangle mesh from a file) has one triangulation, its own, at
// weight 1: its hinges are as skewed as its triangles make them (docs/meshes.md).

#include <array>
#include <vector>

#include "sim/grid.h"

namespace weft::sim {

using Triangles = std::vector<std::array<Index, 3>>;

// [0]: each quad (q0, q1, q2, q3) split along q0–q2 (ClothMesh::triangles()); [1]: along q1–q3.
// Both counter-clockwise like the quads. Each split covers the cloth once: a term summing over
// both weights each by split_weight(mesh) = ½. A mesh without a grid: its triangles alone,
// weight 1.
inline std::vector<Triangles> quad_triangulations(const ClothMesh& mesh) {
  if (!mesh.has_grid()) return {mesh.faces};
  std::vector<Triangles> splits(2);
  for (Triangles& t : splits) t.reserve(2 * mesh.quads.size());
  for (const auto& q : mesh.quads) {
    splits[0].push_back({q[0], q[1], q[2]});
    splits[0].push_back({q[0], q[2], q[3]});
    splits[1].push_back({q[0], q[1], q[3]});
    splits[1].push_back({q[1], q[2], q[3]});
  }
  return splits;
}

inline constexpr double kSplitWeight = 0.5;  // each of the two splits of a grid
inline double split_weight(const ClothMesh& mesh) { return mesh.has_grid() ? kSplitWeight : 1.0; }

}  // namespace weft::sim
