#pragma once
// Test scenes for self-collision: a square sheet, and the sheet rolled into a spiral.

#include <cmath>
#include <map>

#include "base/constants.h"
#include "sim/grid.h"

namespace weft::sim {

inline ClothMesh sheet(Index n, SpecimenShape shape = SpecimenShape::rectangle) {
  GridSpec spec;
  spec.nu = spec.nv = n;
  spec.shape = shape;
  spec.origin = Vec3(-0.5, -0.5, 0.3);
  return make_grid(spec);
}

// Rolls the sheet about the weft (y) axis along the spiral r = r0 + gap·φ/2π, the warp
// coordinate u becoming arc length along it, so that consecutive layers are `gap` apart.
inline Matrix3X rolled(const ClothMesh& mesh, double r0_m, double gap_m) {
  const double b = gap_m / (2.0 * base::kPi);
  const auto arc = [&](double phi) {  // ∫₀^φ sqrt(r² + b²) dφ, by the midpoint rule
    const int n = 2000;
    double s = 0.0;
    for (int k = 0; k < n; ++k) {
      const double r = r0_m + b * (phi * (k + 0.5) / n);
      s += std::sqrt(r * r + b * b) * phi / n;
    }
    return s;
  };
  std::map<double, double> phi_at;  // u → φ, by bisection, once per grid column
  Matrix3X x = mesh.rest_positions;
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    const double u = mesh.material_coords[static_cast<std::size_t>(v)].x();
    if (!phi_at.count(u)) {
      double lo = 0.0, hi = u / r0_m;  // arc(φ) ≥ r0 φ
      for (int it = 0; it < 50; ++it) (arc(0.5 * (lo + hi)) < u ? lo : hi) = 0.5 * (lo + hi);
      phi_at[u] = 0.5 * (lo + hi);
    }
    const double phi = phi_at[u], r = r0_m + b * phi;
    x.row(v) = Eigen::RowVector3d(r * std::sin(phi), mesh.rest_positions(v, 1), 0.5 - r * std::cos(phi));
  }
  return x;
}

}  // namespace weft::sim
