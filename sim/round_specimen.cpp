// The disc meshed in rings (see round_specimen.h).

#include "sim/round_specimen.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/constants.h"
#include "sim/triangle_cloth.h"

namespace weft::sim {
namespace {

// Index of vertex m of ring k (ring 0: the centre alone).
Index ring_vertex(Index k, Index m) {
  return k == 0 ? 0 : 1 + 3 * k * (k - 1) + m;
}

// The triangles between ring k − 1 and ring k ≥ 1 (round_specimen.h): walking both rings
// counter-clockwise from angle 0, each triangle steps the ring whose next vertex comes first in
// angle; the angles 2πm/(6k) are compared exactly, in integers. The rings' vertices meet in
// angle on the six spokes φ = 60°·s; there the inner ring steps first, so that the spoke's
// radial edge is a side (the triangles of a hexagonal lattice, 43.7°–90° on a circle; stepping
// the outer ring first makes a 30°–30°–120° triangle at each spoke).
void join_rings(Index k, std::vector<std::vector<Index>>& faces) {
  const Index outer = 6 * k;
  if (k == 1) {
    for (Index m = 0; m < outer; ++m)
      faces.push_back({0, ring_vertex(1, m), ring_vertex(1, (m + 1) % outer)});
    return;
  }
  const Index inner = 6 * (k - 1);
  Index i = 0, j = 0;  // steps taken along the inner and the outer ring
  while (i < inner || j < outer) {
    // Next angles (i + 1)/inner and (j + 1)/outer of a turn: the outer one first when <.
    const bool step_outer = j < outer && (i == inner || (j + 1) * inner < (i + 1) * outer);
    if (step_outer) {
      faces.push_back(
          {ring_vertex(k - 1, i % inner), ring_vertex(k, j), ring_vertex(k, (j + 1) % outer)});
      ++j;
    } else {
      faces.push_back(
          {ring_vertex(k - 1, i), ring_vertex(k, j % outer), ring_vertex(k - 1, (i + 1) % inner)});
      ++i;
    }
  }
}

}  // namespace

Index round_specimen_rings(const GridSpec& spec) {
  return std::max<Index>(1, std::max(spec.nu, spec.nv) / 2);  // ⌈(n − 1)/2⌉ = ⌊n/2⌋
}

ClothMesh make_round_specimen(const GridSpec& spec) {
  check_grid_spec(spec);
  const Index rings = round_specimen_rings(spec);
  const double a = 0.5 * spec.size_u_m, b = 0.5 * spec.size_v_m;
  ClothPattern pattern;
  pattern.origin = spec.origin;
  pattern.warp_axis = spec.warp_axis;
  pattern.weft_axis = spec.weft_axis;
  pattern.material_coords.reserve(static_cast<std::size_t>(ring_vertex(rings + 1, 0)));
  pattern.material_coords.emplace_back(a, b);
  for (Index k = 1; k <= rings; ++k) {
    const double rho = static_cast<double>(k) / static_cast<double>(rings);
    for (Index m = 0; m < 6 * k; ++m) {
      const double phi = 2.0 * base::kPi * static_cast<double>(m) / static_cast<double>(6 * k);
      pattern.material_coords.emplace_back(a + a * rho * std::cos(phi),
                                           b + b * rho * std::sin(phi));
    }
    join_rings(k, pattern.faces);
  }
  const Index n = static_cast<Index>(pattern.material_coords.size());
  pattern.start_positions.resize(n, 3);
  for (Index v = 0; v < n; ++v) {
    const Vec2& uv = pattern.material_coords[static_cast<std::size_t>(v)];
    pattern.start_positions.row(v) =
        (spec.origin + uv.x() * spec.warp_axis + uv.y() * spec.weft_axis).transpose();
  }
  return make_pattern_cloth(pattern);
}

}  // namespace weft::sim
