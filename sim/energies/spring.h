#pragma once
// Linear (Hookean) spring between two vertices: E = ½ k (|xb − xa| − l)².
// Pure kernels: small Eigen values in, value or gradient out.

#include <cmath>

#include "sim/types.h"

namespace weft::sim {

inline double spring_energy(const Vec3& xa, const Vec3& xb, double rest_m, double k_N_m) {
  const double stretch = (xb - xa).norm() - rest_m;
  return 0.5 * k_N_m * stretch * stretch;
}

// Gradient of spring_energy with respect to xb (the gradient with respect to xa is its
// negative); the force on b is minus this. A zero-length spring has no direction: gradient 0.
inline Vec3 spring_gradient_b(const Vec3& xa, const Vec3& xb, double rest_m, double k_N_m) {
  const Vec3 d = xb - xa;
  const double len = d.norm();
  if (len == 0.0) return Vec3::Zero();
  return (k_N_m * (len - rest_m) / len) * d;
}

// A spring whose energy depends on its length alone, E(|d|) (a nonlinear stretch law): the
// gradient with respect to xb is f d̂ for the force along it f = dE/d|d| (N, > 0 stretched).
inline Vec3 spring_gradient_b_from_force(const Vec3& xa, const Vec3& xb, double force_N) {
  const Vec3 d = xb - xa;
  const double len = d.norm();
  if (len == 0.0) return Vec3::Zero();
  return (force_N / len) * d;
}

}  // namespace weft::sim
