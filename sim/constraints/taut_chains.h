#pragma once
// Chains of warp or weft edges pulled straight between two still pins.
//
// A row (or column) of inextensible edges whose two end vertices are pinned exactly their rest
// length along the chain apart can only be straight: every vertex between them is determined,
// at its rest distance along the segment. Projection would rediscover that each step, and
// badly: transverse motion of a straight chain changes its constraints only to second order (a
// singular root), so a chain sagged by the unconstrained step is pulled back straight by
// Newton-type iterations that converge linearly — on the 128² two-corner hang the top edge
// took 70 iterations per step, 36 of the first 60 steps missing the tolerance after 100. Held
// as pins instead (their edges then join two pins and drop out of the projection), the same
// hang needs about 1.2 iterations per step. Exact, not an approximation: the chain has no
// other configuration. Only chains whose ends stay still qualify; one that is slack, stretched,
// or has a moving end is left to the projection.

#include <vector>

#include "sim/grid.h"

namespace weft::sim {

struct TautChains {
  std::vector<Index> vertices;  // sorted, unique: the chains' interior vertices
  int chains = 0;
};

// The taut chains of `mesh` at positions x (#V×3, m): maximal runs of existing warp edges along
// a grid row, or weft edges along a column, between two vertices of `still_pins` with only free
// used vertices between them (a vertex of `moving_pins` breaks a chain), whose ends are their
// rest length along the chain apart and whose every edge is at its rest length, both within
// `relative_tolerance`.
TautChains find_taut_chains(const ClothMesh& mesh, const Matrix3X& x,
                            const std::vector<Index>& still_pins,
                            const std::vector<Index>& moving_pins = {},
                            double relative_tolerance = 1e-9);

}  // namespace weft::sim
