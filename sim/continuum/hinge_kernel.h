#pragma once
// Bending across one interior edge (a "hinge"): the dihedral angle θ between its two triangles
// and the energy E = ½ k (θ − θ0)². Pure kernels. With k = B |e|² / (A1 + A2) — B the bending
// rigidity across the edge (N·m), |e| its rest length, A1 + A2 the rest areas of its two
// triangles — this is ½ B κ² over the hinge's area |e| l⊥ with the curvature κ = θ / l⊥ and
// l⊥ = (A1 + A2)/|e| the mean of the two triangle heights over the edge (seed 004, bending
// "κ = θ / l⊥"; the area weighting follows Grinspun et al.'s discrete shells, with each edge
// taking the whole of its two triangles because, on a warp/weft grid bent along one direction,
// only one edge family of three bends).
//
// Vertices: a, b the edge; c the third vertex of triangle 1 = (a, b, c); d that of triangle 2
// = (b, a, d), so that both normals N1 = (b − a) × (c − a), N2 = (d − a) × (b − a) agree on a
// flat pair. θ = atan2((n̂1 × n̂2) · ê, n̂1 · n̂2) ∈ (−π, π], signed, 0 when flat. Gradients
// (h_c = |N1|/|e| the height of c over the edge, s_c = (c − a)·e/|e|² where c projects on it):
//   ∂θ/∂c = −n̂1 / h_c,   ∂θ/∂d = −n̂2 / h_d,
//   ∂θ/∂a = −(1 − s_c) ∂θ/∂c − (1 − s_d) ∂θ/∂d,   ∂θ/∂b = −s_c ∂θ/∂c − s_d ∂θ/∂d.
// The stiffness used is the Gauss–Newton k ∇θ ∇θᵀ: PSD, and exact wherever θ = θ0 (the omitted
// k (θ − θ0) ∇²θ vanishes there), which is where implicit Euler needs it most: bending is weak
// next to stretch, and the force is exact whatever the stiffness.

#include <array>
#include <cmath>

#include "sim/types.h"

namespace weft::sim {

using Vec12 = Eigen::Matrix<double, 12, 1>;

// θ (rad); 0 when either triangle is degenerate.
inline double hinge_angle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 e = b - a;
  const Vec3 n1 = e.cross(c - a), n2 = (d - a).cross(e);
  const double l1 = n1.norm(), l2 = n2.norm(), le = e.norm();
  if (l1 == 0.0 || l2 == 0.0 || le == 0.0) return 0.0;
  const Vec3 u1 = n1 / l1, u2 = n2 / l2;
  return std::atan2(u1.cross(u2).dot(e / le), u1.dot(u2));
}

// ∇θ with respect to (a, b, c, d), 1/m; zero when degenerate.
inline Vec12 hinge_angle_gradient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Vec12 g = Vec12::Zero();
  const Vec3 e = b - a;
  const Vec3 n1 = e.cross(c - a), n2 = (d - a).cross(e);
  const double l1sq = n1.squaredNorm(), l2sq = n2.squaredNorm(), lesq = e.squaredNorm();
  if (l1sq == 0.0 || l2sq == 0.0 || lesq == 0.0) return g;
  const double le = std::sqrt(lesq);
  const Vec3 gc = -le / l1sq * n1;  // −n̂1 / h_c with h_c = |N1| / |e|
  const Vec3 gd = -le / l2sq * n2;
  const double sc = (c - a).dot(e) / lesq, sd = (d - a).dot(e) / lesq;
  g.segment<3>(0) = -(1.0 - sc) * gc - (1.0 - sd) * gd;
  g.segment<3>(3) = -sc * gc - sd * gd;
  g.segment<3>(6) = gc;
  g.segment<3>(9) = gd;
  return g;
}

inline double hinge_energy(double theta, double rest_theta, double k_Nm) {
  const double d = theta - rest_theta;
  return 0.5 * k_Nm * d * d;
}

}  // namespace weft::sim
