#pragma once
// Hessian of the linear spring energy E = ½ k (|xb − xa| − l)² (sim/energies/spring.h), for
// implicit integration (Baraff & Witkin 1998: the force Jacobian ∂f/∂x = −∂²E/∂x²).
//
// With d = xb − xa and d̂ = d / |d|, the 3×3 block with respect to xb is
//   H = ∂²E/∂xb² = k [ d̂d̂ᵀ + (1 − l/|d|) (I − d̂d̂ᵀ) ]          (N/m)
// and the full 6×6 Hessian with respect to (xa, xb) is [H −H; −H H]. Pure kernels: small Eigen
// values in, a 3×3 block out.
//
// H has the eigenvalue k along d̂ and k (1 − l/|d|) twice across it. A compressed spring
// (|d| < l) therefore has negative transverse eigenvalues — it buckles — and an implicit system
// built from it can be indefinite. spring_hessian_b_projected clamps the transverse factor at 0,
// which is the projection of H onto the positive semi-definite cone (the nearest PSD matrix in
// the Frobenius norm, since H's eigenvectors are explicit); the 6×6 [H −H; −H H] = [1 −1; −1 1]
// ⊗ H is then PSD too.

#include <algorithm>
#include <cmath>

#include "sim/types.h"

namespace weft::sim {

namespace detail {
// k [d̂d̂ᵀ + c (I − d̂d̂ᵀ)] for a non-zero d.
inline Mat3 spring_hessian_from_factor(const Vec3& d, double len, double k_N_m, double c) {
  const Vec3 u = d / len;
  const Mat3 uut = u * u.transpose();
  return k_N_m * (uut + c * (Mat3::Identity() - uut));
}
}  // namespace detail

// ∂²E/∂xb² at (xa, xb), N/m, symmetric 3×3. A zero-length spring has no direction (its true
// Hessian is unbounded): returns 0, like spring_gradient_b returns a zero gradient there.
inline Mat3 spring_hessian_b(const Vec3& xa, const Vec3& xb, double rest_m, double k_N_m) {
  const Vec3 d = xb - xa;
  const double len = d.norm();
  if (len == 0.0) return Mat3::Zero();
  return detail::spring_hessian_from_factor(d, len, k_N_m, 1.0 - rest_m / len);
}

// As spring_hessian_b with the transverse factor (1 − l/|d|) clamped at 0: equal to it for a
// stretched spring, k d̂d̂ᵀ for a compressed one. Positive semi-definite, eigenvalues in [0, k].
inline Mat3 spring_hessian_b_projected(const Vec3& xa, const Vec3& xb, double rest_m,
                                       double k_N_m) {
  const Vec3 d = xb - xa;
  const double len = d.norm();
  if (len == 0.0) return Mat3::Zero();
  return detail::spring_hessian_from_factor(d, len, k_N_m, std::max(0.0, 1.0 - rest_m / len));
}

// ∂²E/∂xb² of a spring whose energy depends on its length alone, E(|d|), with the force along it
// f = dE/d|d| (N) and the axial stiffness a = d²E/d|d|² (N/m): a d̂d̂ᵀ + (f/|d|)(I − d̂d̂ᵀ). For
// E = ½ k (|d| − l)² this is spring_hessian_b. Projected onto the PSD cone, both factors are
// clamped at 0. Zero for a zero-length spring, like the gradient.
inline Mat3 spring_hessian_b_from_force(const Vec3& xa, const Vec3& xb, double force_N,
                                        double axial_N_m, bool project_psd) {
  const Vec3 d = xb - xa;
  const double len = d.norm();
  if (len == 0.0) return Mat3::Zero();
  const Vec3 u = d / len;
  const Mat3 uut = u * u.transpose();
  const double a = project_psd ? std::max(0.0, axial_N_m) : axial_N_m;
  const double t = project_psd ? std::max(0.0, force_N / len) : force_N / len;
  return a * uut + t * (Mat3::Identity() - uut);
}

}  // namespace weft::sim
