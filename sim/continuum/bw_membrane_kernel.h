#pragma once
// Baraff–Witkin membrane of one triangle (seed 004, "Large steps in cloth simulation", §4.2):
// stretch and shear from the deformation map w(u, v) of the triangle's rest material
// coordinates, anisotropic, integrated over the rest area. Pure kernels.
//
// The triangle's vertices x0, x1, x2 (m) have rest material coordinates (u_k, v_k) (m). The map
// is affine on the triangle, with the two columns
//   [w_u w_v] = [x1 − x0, x2 − x0] D⁻¹,   D = [u1 − u0, u2 − u0; v1 − v0, v2 − v0],
// so w_u = Σ_k α_k x_k and w_v = Σ_k β_k x_k with α, β from D⁻¹ (each summing to 0). Energy:
//   E = A [ ½ Y_u S_u² + ½ Y_v S_v² + ½ G γ² ],
//   S_u = ‖w_u‖ − 1, S_v = ‖w_v‖ − 1                  (warp and weft strain)
//   γ = asin(ŵ_u · ŵ_v) = π/2 − ∠(w_u, w_v)           (shear angle: the warp–weft angle's
//                                                     deviation from π/2, 0 at rest)
// with A the rest area (m²), Y_u, Y_v the tensile rigidities and G the shear rigidity (N/m, per
// unit strain or radian). Baraff–Witkin's shear condition is A w_u·w_v, which equals A γ only to
// first order; the angle itself keeps G the measured shear rigidity at large shear too.
//
// Derivatives are taken in w-space (6 coordinates: w_u then w_v) and mapped to the vertices by
// the constant α, β: ∂E/∂x_k = α_k ∂E/∂w_u + β_k ∂E/∂w_v, and the 9×9 stiffness block (k, l) is
// Σ over (a, b) ∈ {u, v}² of coef_a(k) coef_b(l) ∂²E/∂w_a∂w_b.
//
// Exact w-space Hessian (c = ŵ_u·ŵ_v, P_u = I − ŵ_uŵ_uᵀ, γ' = 1/√(1 − c²), γ'' = c γ'³):
//   stretch   ∂²/∂w_u² ½ S_u² = ŵ_uŵ_uᵀ + (1 − 1/‖w_u‖) P_u
//   shear     ∂²/∂w² ½ γ² = (γ'² + γ γ'') ∇c ∇cᵀ + γ γ' ∇²c,   ∇_{w_u} c = P_u ŵ_v / ‖w_u‖,
//             ∂²c/∂w_u² = −[ŵ_u gᵀ + g ŵ_uᵀ + c P_u] / ‖w_u‖² with g = P_u ŵ_v,
//             ∂²c/∂w_u∂w_v = P_u P_v / (‖w_u‖ ‖w_v‖).
// The PSD projection (implicit Euler) clamps the stretch's transverse factor (1 − 1/‖w‖) at 0,
// as for a spring, and keeps only the Gauss–Newton part γ'² ∇c∇cᵀ of the shear: both are PSD,
// so the sum is. They are exact at rest.

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/types.h"

namespace weft::sim {

struct BwTriangleRest {
  std::array<double, 3> alpha{};  // w_u = Σ alpha_k x_k, 1/m
  std::array<double, 3> beta{};   // w_v = Σ beta_k x_k, 1/m
  double area_m2 = 0.0;
};

struct BwRigidities {
  double warp_N_m = 0.0;   // Y_u
  double weft_N_m = 0.0;   // Y_v
  double shear_N_m = 0.0;  // G
};

// From the rest material coordinates; area 0 (and zero coefficients) for a degenerate triangle.
inline BwTriangleRest bw_triangle_rest(const Vec2& m0, const Vec2& m1, const Vec2& m2) {
  Eigen::Matrix2d D;
  D.col(0) = m1 - m0;
  D.col(1) = m2 - m0;
  const double det = D.determinant();
  BwTriangleRest r;
  if (det == 0.0) return r;
  const Eigen::Matrix2d Di = D.inverse();
  // w_u = (x1 − x0) Di(0,0) + (x2 − x0) Di(1,0); w_v likewise with column 1.
  r.alpha = {-Di(0, 0) - Di(1, 0), Di(0, 0), Di(1, 0)};
  r.beta = {-Di(0, 1) - Di(1, 1), Di(0, 1), Di(1, 1)};
  r.area_m2 = 0.5 * std::abs(det);
  return r;
}

struct BwMap {
  Vec3 wu, wv;
};

inline BwMap bw_map(const BwTriangleRest& r, const Vec3& x0, const Vec3& x1, const Vec3& x2) {
  return {r.alpha[0] * x0 + r.alpha[1] * x1 + r.alpha[2] * x2,
          r.beta[0] * x0 + r.beta[1] * x1 + r.beta[2] * x2};
}

namespace detail {
// Cosine of the warp–weft angle, kept inside (−1, 1) so that asin and its derivatives stay
// finite for a collapsed triangle.
inline double bw_cosine(const Vec3& a_hat, const Vec3& b_hat) {
  return std::clamp(a_hat.dot(b_hat), -1.0 + 1e-12, 1.0 - 1e-12);
}
}  // namespace detail

// E (J), and the gradient with respect to (w_u, w_v) (N/m · m² = N·m per unit w).
inline double bw_membrane_energy(const BwTriangleRest& r, const BwRigidities& k, const BwMap& w) {
  const double lu = w.wu.norm(), lv = w.wv.norm();
  double e =
      0.5 * k.warp_N_m * (lu - 1.0) * (lu - 1.0) + 0.5 * k.weft_N_m * (lv - 1.0) * (lv - 1.0);
  if (k.shear_N_m != 0.0 && lu > 0.0 && lv > 0.0) {
    const double gamma = std::asin(detail::bw_cosine(w.wu / lu, w.wv / lv));
    e += 0.5 * k.shear_N_m * gamma * gamma;
  }
  return r.area_m2 * e;
}

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

inline Vec6 bw_membrane_gradient_w(const BwTriangleRest& r, const BwRigidities& k, const BwMap& w) {
  Vec6 g = Vec6::Zero();
  const double lu = w.wu.norm(), lv = w.wv.norm();
  if (lu == 0.0 || lv == 0.0) return g;  // collapsed: no direction
  const Vec3 uh = w.wu / lu, vh = w.wv / lv;
  g.head<3>() = k.warp_N_m * (lu - 1.0) * uh;
  g.tail<3>() = k.weft_N_m * (lv - 1.0) * vh;
  if (k.shear_N_m != 0.0) {
    const double c = detail::bw_cosine(uh, vh);
    const double gamma = std::asin(c), dgamma = 1.0 / std::sqrt(1.0 - c * c);
    const double s = k.shear_N_m * gamma * dgamma;
    g.head<3>() += s * (vh - c * uh) / lu;
    g.tail<3>() += s * (uh - c * vh) / lv;
  }
  return r.area_m2 * g;
}

// ∂²E/∂w², exact, or PSD-projected as described in the header comment.
inline Mat6 bw_membrane_hessian_w(const BwTriangleRest& r, const BwRigidities& k, const BwMap& w,
                                  bool project_psd) {
  Mat6 H = Mat6::Zero();
  const double lu = w.wu.norm(), lv = w.wv.norm();
  if (lu == 0.0 || lv == 0.0) return H;
  const Vec3 uh = w.wu / lu, vh = w.wv / lv;
  const Mat3 I = Mat3::Identity();
  const Mat3 Pu = I - uh * uh.transpose(), Pv = I - vh * vh.transpose();
  const auto transverse = [&](double len) {
    const double t = 1.0 - 1.0 / len;
    return project_psd ? std::max(0.0, t) : t;
  };
  H.topLeftCorner<3, 3>() = k.warp_N_m * (uh * uh.transpose() + transverse(lu) * Pu);
  H.bottomRightCorner<3, 3>() = k.weft_N_m * (vh * vh.transpose() + transverse(lv) * Pv);
  if (k.shear_N_m != 0.0) {
    const double c = detail::bw_cosine(uh, vh);
    const double gamma = std::asin(c), d1 = 1.0 / std::sqrt(1.0 - c * c), d2 = c * d1 * d1 * d1;
    Vec6 dc;
    const Vec3 gu = vh - c * uh, gv = uh - c * vh;  // P_u v̂, P_v û
    dc.head<3>() = gu / lu;
    dc.tail<3>() = gv / lv;
    const double gn = project_psd ? d1 * d1 : d1 * d1 + gamma * d2;
    H += k.shear_N_m * gn * dc * dc.transpose();
    if (!project_psd) {
      const double s = k.shear_N_m * gamma * d1;
      H.topLeftCorner<3, 3>() -=
          s * (uh * gu.transpose() + gu * uh.transpose() + c * Pu) / (lu * lu);
      H.bottomRightCorner<3, 3>() -=
          s * (vh * gv.transpose() + gv * vh.transpose() + c * Pv) / (lv * lv);
      const Mat3 cross = s * Pu * Pv / (lu * lv);
      H.topRightCorner<3, 3>() += cross;
      H.bottomLeftCorner<3, 3>() += cross.transpose();
    }
  }
  return r.area_m2 * H;
}

}  // namespace weft::sim
