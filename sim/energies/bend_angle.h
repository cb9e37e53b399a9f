#pragma once
// Angular bending spring on three consecutive vertices of a warp or weft line (the skip-one
// stencil x0, x1, x2): E = ½ k (θ − θ0)², θ the turning angle between e1 = x1 − x0 and
// e2 = x2 − x1. Kass (seed 004, "discretized circle"): with k = B·w / l̄ — B the bending
// rigidity (N·m), w the width of cloth the line stands for, l̄ the mean rest edge length — the
// energy approximates ½ B κ² integrated over the area, whatever the sampling.

#include <array>
#include <cmath>

#include <Eigen/Eigenvalues>

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

// The derivatives of a stencil's energy E(θ) with respect to its turning angle: dE/dθ (N·m)
// and d²E/dθ² (N·m per radian), at θ; d2E_at_flat: d²E/dθ² at θ = θ0 (the limit that sets the
// forces and stiffness of a nearly straight stencil, where the bending direction is undefined).
struct AngleEnergySlope {
  double dE = 0.0;
  double d2E = 0.0;
  double d2E_at_rest = 0.0;
};

// The factor dE/dθ / sin θ of the gradients below, finite as θ → 0; false when the bending
// direction is undefined (a straight stencil with a non-zero rest angle, or a folded-back one).
inline bool bend_angle_factor(double theta, double s, double c, double rest_angle,
                              const AngleEnergySlope& slope, double& factor) {
  if (s > 1e-7) {
    factor = slope.dE / s;
    return true;
  }
  if (rest_angle == 0.0 && c > 0.0) {
    factor = slope.d2E_at_rest * (1.0 + theta * theta / 6.0);  // ≈ E''(0) θ / sin θ
    return true;
  }
  return false;
}

// Gradients of a stencil energy E(θ) with respect to x0, x1, x2 (they sum to zero);
// slope_at(θ) gives its AngleEnergySlope.
template <class SlopeAt>
std::array<Vec3, 3> bend_angle_gradient(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                        double rest_angle, SlopeAt&& slope_at) {
  const Vec3 e1 = x1 - x0, e2 = x2 - x1;
  const double l1 = e1.norm(), l2 = e2.norm();
  if (l1 == 0.0 || l2 == 0.0) return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const Vec3 a = e1 / l1, b = e2 / l2;
  const double c = a.dot(b);
  const double s = a.cross(b).norm();
  // dθ/de1 = −(b − c a) / (l1 s), dθ/de2 = −(a − c b) / (l2 s). (b − c a) has length s, so
  // the force is finite as θ → 0.
  const double theta = std::atan2(s, c);
  double factor;  // dE/dθ / sin θ
  if (!bend_angle_factor(theta, s, c, rest_angle, slope_at(theta), factor))
    return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const Vec3 g1 = -factor * (b - c * a) / l1;  // ∂E/∂e1
  const Vec3 g2 = -factor * (a - c * b) / l2;  // ∂E/∂e2
  return {-g1, g1 - g2, g2};
}

// The linear law E = ½ k (θ − θ0)²: dE/dθ = k (θ − θ0), d²E/dθ² = k.
inline AngleEnergySlope linear_angle_slope(double theta, double rest_angle, double k_Nm) {
  return {k_Nm * (theta - rest_angle), k_Nm, k_Nm};
}

// Gradients of bend_angle_energy with respect to x0, x1, x2 (they sum to zero).
inline std::array<Vec3, 3> bend_angle_gradient(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                               double rest_angle, double k_Nm) {
  return bend_angle_gradient(x0, x1, x2, rest_angle, [&](double theta) {
    return linear_angle_slope(theta, rest_angle, k_Nm);
  });
}

// ∂²E/∂x² of a stencil energy E(θ) (slope_at as above), 9×9 (x0, x1, x2), into H. With c = cos θ = â·b̂ of the edge
// directions, θ = arccos c gives ∇θ = −∇c / s and ∇²θ = −∇²c / s − c ∇c ∇cᵀ / s³, so
//   ∇²E = (E'' − E' c / s) ∇c ∇cᵀ / s² − (E' / s) ∇²c,
// with, over the edges e1 = x1 − x0 and e2 = x2 − x1 (lengths l1, l2),
//   ∂²c/∂e1² = (−(â b̂ᵀ + b̂ âᵀ) + 3c â âᵀ − c I) / l1²,  ∂²c/∂e2² the same with â ↔ b̂, l2,
//   ∂²c/∂e1∂e2 = (I − â âᵀ − b̂ b̂ᵀ + c â b̂ᵀ) / (l1 l2).
// At θ → 0 the first term vanishes (E'' − E'/θ → 0) and E'/s → E''(θ0): ∇²E = −E'' ∇²c.
// project_psd: the 6×6 edge-space Hessian's negative eigenvalues are set to zero before it is
// mapped to the vertices, which keeps the result positive semi-definite.
template <class SlopeAt>
void bend_angle_hessian(const Vec3& x0, const Vec3& x1, const Vec3& x2, double rest_angle,
                        SlopeAt&& slope_at, bool project_psd, Eigen::Matrix<double, 9, 9>& H) {
  H.setZero();
  const Vec3 e1 = x1 - x0, e2 = x2 - x1;
  const double l1 = e1.norm(), l2 = e2.norm();
  if (l1 == 0.0 || l2 == 0.0) return;
  const Vec3 a = e1 / l1, b = e2 / l2;
  const double c = a.dot(b);
  const double s = a.cross(b).norm();
  const AngleEnergySlope slope = slope_at(std::atan2(s, c));
  double factor;  // E' / s
  if (!bend_angle_factor(std::atan2(s, c), s, c, rest_angle, slope, factor)) return;
  const Mat3 I = Mat3::Identity();
  const Mat3 ab = a * b.transpose() + b * a.transpose();
  Eigen::Matrix<double, 6, 6> He;
  He.block<3, 3>(0, 0) = (-ab + 3.0 * c * a * a.transpose() - c * I) / (l1 * l1);
  He.block<3, 3>(3, 3) = (-ab + 3.0 * c * b * b.transpose() - c * I) / (l2 * l2);
  He.block<3, 3>(0, 3) = (I - a * a.transpose() - b * b.transpose() + c * a * b.transpose()) / (l1 * l2);
  He.block<3, 3>(3, 0) = He.block<3, 3>(0, 3).transpose();
  He *= -factor;
  if (s > 1e-7) {
    Eigen::Matrix<double, 6, 1> gc;  // ∇c
    gc << (b - c * a) / l1, (a - c * b) / l2;
    He += (slope.d2E - factor * c) / (s * s) * gc * gc.transpose();
  }
  if (project_psd) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(He);
    const Eigen::Matrix<double, 6, 1> lambda = eig.eigenvalues().cwiseMax(0.0);
    He = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
  }
  // e1 = x1 − x0, e2 = x2 − x1: H = Dᵀ He D.
  Eigen::Matrix<double, 6, 9> D = Eigen::Matrix<double, 6, 9>::Zero();
  D.block<3, 3>(0, 0) = -I;
  D.block<3, 3>(0, 3) = I;
  D.block<3, 3>(3, 3) = -I;
  D.block<3, 3>(3, 6) = I;
  H = D.transpose() * He * D;
}

}  // namespace weft::sim
