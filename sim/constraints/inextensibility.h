#pragma once
// Inextensibility of one warp or weft edge (Goldenthal et al. 2007, seed 000, eqs. 1–2):
//   C(pa, pb) = |pb − pa|² / l − l,   ∇_pb C = 2 (pb − pa) / l = −∇_pa C.
// C is zero at the rest length l, positive when stretched; C / (2l) ≈ strain for small strain.
// Pure kernels.

#include "sim/types.h"

namespace weft::sim {

inline double edge_constraint(const Vec3& pa, const Vec3& pb, double rest_m) {
  return (pb - pa).squaredNorm() / rest_m - rest_m;
}

inline Vec3 edge_constraint_gradient_b(const Vec3& pa, const Vec3& pb, double rest_m) {
  return (2.0 / rest_m) * (pb - pa);
}

// |pb − pa| / l − 1, the engineering strain the tolerance is measured in.
inline double edge_strain(const Vec3& pa, const Vec3& pb, double rest_m) {
  return (pb - pa).norm() / rest_m - 1.0;
}

}  // namespace weft::sim
