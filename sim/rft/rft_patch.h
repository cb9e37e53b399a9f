#pragma once
// The element patch of the rotation-free triangles (seed 002, Zhou & Sze, §2.1 and Fig. 4(a)):
// a triangle and the three vertices opposite it across its edges, i.e. the third vertex of each
// edge-adjacent triangle. On the cloth's boundary an edge has no neighbour and its slot is
// absent (rft_bending_kernel.h and rft6_membrane_kernel.h say how each model treats it).
//
// Slot layout, shared by the kernels and the ForceTerm stencils:
//   slots 0, 1, 2    the triangle t0, t1, t2 (counter-clockwise about warp × weft)
//   slots 3 … n − 1  the present opposite vertices, in the order p0, p1, p2, where p_k lies
//                    across the edge (t_{k+1}, t_{k+2}) opposite t_k
// so a patch has n = 3 + (number of present neighbours) ≤ 6 vertices.

#include <array>
#include <vector>

#include "sim/grid.h"
#include "sim/types.h"

namespace weft::sim {

inline constexpr int kRftPatchSlots = 6;

struct RftPatch {
  std::array<Index, kRftPatchSlots> vertices{};  // mesh vertex of each slot (first `size` valid)
  std::array<int, 3> opposite_slot{-1, -1, -1};  // slot of p_k, or −1 on a boundary edge
  int size = 3;                                  // 3 … 6
  std::size_t triangle = 0;                      // index into mesh.triangles()
};

// One patch per triangle of mesh.triangles(), in that order. Throws std::invalid_argument if an
// edge is shared by more than two triangles or two triangles disagree on orientation.
std::vector<RftPatch> make_rft_patches(const ClothMesh& mesh);

// Throws std::invalid_argument "<key>: expected a finite rigidity >= 0, got <value>" otherwise;
// key names the Material field (e.g. "material.bend_warp_Nm").
void check_rft_rigidity(double value, const char* key);

// The rest material coordinates (u, v), m, of a patch's slots; unused slots are zero.
inline std::array<Vec2, kRftPatchSlots> rft_patch_material_coords(const ClothMesh& mesh,
                                                                  const RftPatch& patch) {
  std::array<Vec2, kRftPatchSlots> uv;
  for (int s = 0; s < kRftPatchSlots; ++s)
    uv[static_cast<std::size_t>(s)] = s < patch.size
                                          ? mesh.material_coords[static_cast<std::size_t>(
                                                patch.vertices[static_cast<std::size_t>(s)])]
                                          : Vec2::Zero();
  return uv;
}

// The positions of a patch's slots as the columns of a 3×6 matrix (m); unused columns zero.
using RftPatchPositions = Eigen::Matrix<double, 3, kRftPatchSlots>;
inline RftPatchPositions rft_gather(const Matrix3X& x, const RftPatch& patch) {
  RftPatchPositions X = RftPatchPositions::Zero();
  for (int s = 0; s < patch.size; ++s)
    X.col(s) = x.row(patch.vertices[static_cast<std::size_t>(s)]).transpose();
  return X;
}

// X with slot 0's position subtracted from every column. The RFT strains and curvatures only
// see differences of positions (their slot operators annihilate constants, and vanish on unused
// slots), so the kernels evaluate them on relative positions: no cancellation far from the
// origin.
inline RftPatchPositions rft_relative(const RftPatchPositions& X) {
  return X.colwise() - X.col(0);
}

// f_i −= column i of the 3×6 gradient G (N), for the patch's used slots.
inline void rft_scatter_minus(const Eigen::Matrix<double, 3, kRftPatchSlots>& G,
                              const RftPatch& patch, Matrix3X& f) {
  for (int s = 0; s < patch.size; ++s)
    f.row(patch.vertices[static_cast<std::size_t>(s)]) -= G.col(s).transpose();
}

}  // namespace weft::sim
