#pragma once
// Rectangular warp/weft quad grid: the cloth's rest shape and topology.

#include <array>
#include <string>
#include <vector>

#include "sim/types.h"

namespace weft::sim {

struct GridSpec {
  double size_u_m = 1.0, size_v_m = 1.0;  // extent along warp (u) and weft (v)
  Index nu = 32, nv = 32;                 // vertices along warp and weft, each ≥ 2
  Vec3 origin{0.0, 0.0, 1.0};             // world position of material point (0, 0)
  Vec3 warp_axis{1.0, 0.0, 0.0};          // unit world direction of +u
  Vec3 weft_axis{0.0, 1.0, 0.0};          // unit world direction of +v, orthogonal to warp_axis
};

// Vertex (i, j) — i along warp, j along weft — has index j·nu + i.
struct ClothMesh {
  Index nu = 0, nv = 0;
  Matrix3X rest_positions;                     // #V×3, metres
  std::vector<Vec2> material_coords;           // #V (u, v), metres
  std::vector<std::array<Index, 4>> quads;     // #Q, counter-clockwise about warp×weft: (i,j) (i+1,j) (i+1,j+1) (i,j+1)
  Eigen::VectorXd vertex_area_m2;              // #V lumped (area-weighted) area per vertex

  Index vertex_count() const { return static_cast<Index>(rest_positions.rows()); }
  Index index(Index i, Index j) const { return j * nu + i; }
  // Two triangles per quad, split along the (i,j)–(i+1,j+1) diagonal, same orientation as quads.
  std::vector<std::array<Index, 3>> triangles() const;
};

ClothMesh make_grid(const GridSpec& spec);

}  // namespace weft::sim
