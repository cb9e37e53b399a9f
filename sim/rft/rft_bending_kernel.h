#pragma once
// Bending of one rotation-free triangle (RFT3/RFT6 share it): seed 002, Zhou & Sze, §2.1–2.2,
// eqs. (1)–(4) and (7)–(13). Pure kernels.
//
// Patch (rft_patch.h): the triangle's three vertices and the (up to) three vertices across its
// edges, with rest material coordinates (u, v) in metres (u along the warp). A quadratic
//   w(u, v) = c1 + c2 u + c3 v + c4 u²/2 + c5 v²/2 + c6 u v                       (eq. 1)
// interpolating six nodal values (eq. 2, w = C c) has the constant curvature
//   κ = (w_uu, w_vv, 2 w_uv) = (c4, c5, 2 c6) = L w,   L (3×6) = lower half of C⁻¹  (eq. 3)
// (row 3 doubled), which is taken as the triangle's curvature. L annihilates every affine
// function of (u, v), so for a flat rest shape the corotated displacement derivatives of
// eqs. (10)–(12) are U_,pq = Σ_i L_pq,i x_i: the 3-vectors
//   k_a = Σ_i L_ai x_i   (1/m; a = uu, vv, twist)
// of the deformed positions x_i, and the bending energy (eqs. 4, 11) is
//   E = ½ A Σ_a D_a |k_a|²,     D = diag(B_warp, B_weft, B_twist)  (N·m)
// with A the triangle's rest area (m²). E is exactly quadratic in x, so its Hessian is the
// constant matrix A Lᵀ D L ⊗ I₃ of eq. (13): the paper's constant corotational stiffness is
// the exact Hessian here, PSD, and E is exactly invariant under rigid motions (Σ_i L_ai = 0, and
// a rotation maps each k_a to R k_a).
//
// Poisson's ratio is 0 (D diagonal, as the textile data give no coupling). The twist
// rigidity is Huber's orthotropic-plate value for ν = 0, B_twist = ½ √(B_warp B_weft): it makes
// the energy isotropic (½ B |∇∇w|²) when B_warp = B_weft, and gives the directional rigidity
//   B(θ) = (√B_warp cos²θ + √B_weft sin²θ)²
// for a cylinder whose curvature runs at angle θ to the warp. (Kang & Yu's wool has measured
// 0.027 gf·cm; this rule gives 0.036 gf·cm.)
//
// Boundary (a patch slot missing): seed 002 uses image nodes (Phaal & Calladine 1992a, Zhou &
// Sze 2012) whose conventions it does not restate. Here a free edge carries no bending moment
// normal to it; with ν = 0 that is κ_nn = n_u² w_uu + n_v² w_vv + 2 n_u n_v w_uv = 0, n the
// edge's in-plane normal. Each missing neighbour removes one node and imposes that one linear
// condition on (c4, c5, c6), so the fit stays square: 3 + (3 − m) coefficients from 6 − m
// nodes. It equals an image node whose displacement makes the normal curvature vanish. On a
// grid's boundary (edges along warp or weft) it drops the curvature across the edge and keeps
// the curvature along it exactly.

#include <Eigen/LU>
#include <Eigen/SVD>
#include <array>
#include <cmath>

#include "sim/rft/rft_patch.h"
#include "sim/types.h"

namespace weft::sim {

using RftCurvatureOperator = Eigen::Matrix<double, 3, kRftPatchSlots>;  // L, 1/m² per slot
using RftSlotMatrix = Eigen::Matrix<double, kRftPatchSlots, kRftPatchSlots>;
using RftPatchGradient = Eigen::Matrix<double, 3, kRftPatchSlots>;  // column i = ∂E/∂x_i
using RftPatchHessian = Eigen::Matrix<double, 3 * kRftPatchSlots, 3 * kRftPatchSlots>;

struct RftBendingRest {
  RftCurvatureOperator L = RftCurvatureOperator::Zero();  // rows: w_uu, w_vv, 2 w_uv; 1/m²
  double area_m2 = 0.0;
  bool ok = false;  // false for a degenerate triangle or a patch whose fit is singular
};

struct RftBendingRigidity {
  double warp_Nm = 0.0;   // D_11: curvature along the warp (u)
  double weft_Nm = 0.0;   // D_22: curvature along the weft (v)
  double twist_Nm = 0.0;  // D_33, multiplying (2 w_uv)²
};

// Huber's twist rigidity for ν = 0 (header comment).
inline RftBendingRigidity rft_bending_rigidity(double warp_Nm, double weft_Nm) {
  return {warp_Nm, weft_Nm, 0.5 * std::sqrt(warp_Nm * weft_Nm)};
}

// The curvature operator of a patch from its slots' rest material coordinates (m) and the slot
// of each opposite vertex (−1: free edge, header comment).
inline RftBendingRest rft_bending_rest(const std::array<Vec2, kRftPatchSlots>& uv,
                                       const std::array<int, 3>& opposite_slot) {
  RftBendingRest r;
  const Vec2 e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
  r.area_m2 = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
  if (!(r.area_m2 > 0.0)) return r;
  // Local coordinates centred on the triangle and scaled by its size, for conditioning.
  const Vec2 centre = (uv[0] + uv[1] + uv[2]) / 3.0;
  const double scale_m = std::sqrt(2.0 * r.area_m2);
  // Free-edge conditions κ_nn = 0 as rows acting on (c4, c5, c6).
  Eigen::Matrix<double, 3, 3> conditions = Eigen::Matrix3d::Zero();
  int m = 0, n = 3;
  for (int k = 0; k < 3; ++k) {
    if (opposite_slot[static_cast<std::size_t>(k)] >= 0) {
      ++n;
      continue;
    }
    const Vec2 t =
        (uv[static_cast<std::size_t>((k + 2) % 3)] - uv[static_cast<std::size_t>((k + 1) % 3)])
            .normalized();
    const Vec2 nrm(-t.y(), t.x());
    conditions.row(m++) << nrm.x() * nrm.x(), nrm.y() * nrm.y(), 2.0 * nrm.x() * nrm.y();
  }
  // Z: orthonormal basis (3 × (3 − m)) of the quadratic coefficients that satisfy them.
  Eigen::Matrix3d Z = Eigen::Matrix3d::Identity();
  if (m > 0) {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(conditions, Eigen::ComputeFullV);
    Z = svd.matrixV();  // its last 3 − m columns span the null space of the m conditions
    Z.leftCols(3 - m) = Z.rightCols(3 - m).eval();
  }
  const int q = 3 - m;  // free quadratic coefficients
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> C(n, n);
  for (int s = 0; s < n; ++s) {
    const Vec2 p = (uv[static_cast<std::size_t>(s)] - centre) / scale_m;
    const Eigen::RowVector3d quad(0.5 * p.x() * p.x(), 0.5 * p.y() * p.y(), p.x() * p.y());
    C(s, 0) = 1.0;
    C(s, 1) = p.x();
    C(s, 2) = p.y();
    if (q > 0) C.block(s, 3, 1, q) = quad * Z.leftCols(q);
  }
  Eigen::FullPivLU<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>> lu(C);
  lu.setThreshold(1e-10);
  if (!lu.isInvertible()) return r;
  const auto Cinv = lu.inverse();
  if (q > 0) {
    // (c4, c5, c6) per unit nodal value, in scaled coordinates → per metre² in (u, v).
    const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> c = Z.leftCols(q) * Cinv.bottomRows(q);
    const double to_m = 1.0 / (scale_m * scale_m);
    r.L.block(0, 0, 1, n) = to_m * c.row(0);
    r.L.block(1, 0, 1, n) = to_m * c.row(1);
    r.L.block(2, 0, 1, n) = 2.0 * to_m * c.row(2);
  }
  r.ok = true;
  return r;
}

// The three curvature vectors k_a = Σ_i L_ai x_i as the columns of a 3×3 matrix (1/m).
inline Eigen::Matrix3d rft_curvature_vectors(const RftBendingRest& r, const RftPatchPositions& X) {
  return rft_relative(X) * r.L.transpose();
}

inline Eigen::Vector3d rft_bending_diagonal(const RftBendingRigidity& D) {
  return {D.warp_Nm, D.weft_Nm, D.twist_Nm};
}

// E = ½ A Σ_a D_a |k_a|², J.
inline double rft_bending_energy(const RftBendingRest& r, const RftBendingRigidity& D,
                                 const RftPatchPositions& X) {
  const Eigen::Matrix3d k = rft_curvature_vectors(r, X);
  return 0.5 * r.area_m2 *
         (k.colwise().squaredNorm().transpose().cwiseProduct(rft_bending_diagonal(D))).sum();
}

// ∂E/∂x_i = A Σ_a D_a L_ai k_a (N), as columns.
inline RftPatchGradient rft_bending_gradient(const RftBendingRest& r, const RftBendingRigidity& D,
                                             const RftPatchPositions& X) {
  const Eigen::Matrix3d k = rft_curvature_vectors(r, X);
  return r.area_m2 * k * rft_bending_diagonal(D).asDiagonal() * r.L;
}

// The constant Hessian per slot pair, S = A Lᵀ D L (N/m); the full Hessian is S ⊗ I₃.
inline RftSlotMatrix rft_bending_slot_stiffness(const RftBendingRest& r,
                                                const RftBendingRigidity& D) {
  return r.area_m2 * r.L.transpose() * rft_bending_diagonal(D).asDiagonal() * r.L;
}

}  // namespace weft::sim
