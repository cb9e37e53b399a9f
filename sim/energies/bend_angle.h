#pragma once
// Angular bending spring on three consecutive vertices of a warp or weft line (the skip-one
// stencil x0, x1, x2): E = ½ k (θ − θ0)², θ the turning angle between e1 = x1 − x0 and
// e2 = x2 − x1. Kass (seed 004, "discretized circle"): with k = B·w / l̄ — B the bending
// rigidity (N·m), w the width of cloth the line stands for, l̄ the mean rest edge length — the
// energy approximates ½ B κ² integrated over the area, whatever the sampling.

#include <array>
#include <cmath>

#include "sim/types.h"

namespace weft::sim {

// Turning angle in [0, π] between e1 and e2; 0 when either is zero.
inline double turning_angle(const Vec3& e1, const Vec3& e2) {
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

inline double bend_angle_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2, double rest_angle,
                                double k_Nm) {
  const double d = turning_angle(x1 - x0, x2 - x1) - rest_angle;
  return 0.5 * k_Nm * d * d;
}

// Gradients of bend_angle_energy with respect to x0, x1, x2 (they sum to zero).
inline std::array<Vec3, 3> bend_angle_gradient(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                               double rest_angle, double k_Nm) {
  const Vec3 e1 = x1 - x0, e2 = x2 - x1;
  const double l1 = e1.norm(), l2 = e2.norm();
  if (l1 == 0.0 || l2 == 0.0) return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const Vec3 a = e1 / l1, b = e2 / l2;
  const double c = a.dot(b);
  const double s = a.cross(b).norm();
  const double theta = std::atan2(s, c);
  // dθ/de1 = −(b − c a) / (l1 s), dθ/de2 = −(a − c b) / (l2 s). (b − c a) has length s, so
  // the force is finite as θ → 0; θ/s → 1 there, and (θ − θ0)/s is kept finite the same way.
  const double excess = theta - rest_angle;
  double factor;  // k (θ − θ0) / sin θ
  if (s > 1e-7) {
    factor = k_Nm * excess / s;
  } else if (rest_angle == 0.0 && c > 0.0) {
    factor = k_Nm * (1.0 + theta * theta / 6.0);  // θ/sin θ
  } else {
    return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // direction of bending undefined
  }
  const Vec3 g1 = -factor * (b - c * a) / l1;  // ∂E/∂e1
  const Vec3 g2 = -factor * (a - c * b) / l2;  // ∂E/∂e2
  return {-g1, g1 - g2, g2};
}

}  // namespace weft::sim
