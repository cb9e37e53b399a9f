#pragma once
// Membrane (stretch and shear) of one rotation-free triangle, seed 002 (Zhou & Sze): RFT3's
// constant-strain triangle (§2.3, eqs. 14–15) or RFT6's six-node interpolation (§3, eqs.
// 24–26, after Flores & Oñate's EBST). Pure kernels.
//
// Strain. Green strain in material coordinates (u along warp, v along weft, metres), Voigt
//   ε = (ε_uu, ε_vv, γ = 2 ε_uv),   ε_ab = ½ (F_a · F_b − δ_ab),
// where F = ∂x/∂(u, v) (3×2) is a sum over patch slots F = Σ_i x_i g_iᵀ with constant material
// gradients g_i (1/m) of the shape functions:
//   RFT3: the CST's, g_i = ∇L_i on the triangle (three slots).
//   RFT6: F is evaluated at the mid-points of the three edges and the three Green strains are
//         averaged (one-point rule, §3). With barycentrics L_k of the triangle taken as the
//         parametric coordinates and p_k the vertex across the edge opposite t_k, the six-node
//         functions are N_{t_k} = L_k + L_{k+1} L_{k+2}, N_{p_k} = L_k (L_k − 1)/2 (eq. 24);
//         at the mid-point of edge k (L_k = 0, the others ½) their parametric differentials
//         reduce to the four nodes bounding it (eq. 26):
//           dN_{t_k} = ½ dL_k, dN_{t_k±1} = dL_{k±1} + ½ dL_k, dN_{p_k} = −½ dL_k, others 0,
//         and the chain rule (eq. 25) through J = Σ_i X_i dN_iᵀ (isoparametric in the rest
//         material coordinates X_i) gives g_i = J⁻ᵀ dN_i. On a boundary edge (p_k missing) the
//         edge's strain is the CST strain of the triangle (§3, Fig. 4(b)), so no image node is
//         needed.
// Both strains are then quadratic forms of the patch positions, with constant symmetric slot
// matrices Q_c (1/m², averaged over the mid-edges for RFT6):
//   ε_uu = ½ (Σ_ij Q_uu,ij x_i·x_j − 1),  ε_vv = ½ (Σ_ij Q_vv,ij x_i·x_j − 1),
//   γ    = ½ Σ_ij Q_γ,ij x_i·x_j          (= F_u · F_v, averaged),
//   Q_uu = ⟨g_u g_uᵀ⟩, Q_vv = ⟨g_v g_vᵀ⟩, Q_γ = ⟨g_u g_vᵀ + g_v g_uᵀ⟩
// (g_u, g_v: the slot vectors of the u and v components of the g_i; ⟨⟩ the mid-edge average).
//
// Energy (eq. 15), orthotropic without Poisson coupling, over the rest area A (m²):
//   E = ½ A (Y_u ε_uu² + Y_v ε_vv² + G γ²),   Y_u, Y_v, G in N/m.
// Writing e_c = (ε_uu, ε_vv, γ), d_c = (Y_u, Y_v, G), P_c = (Q_uu, Q_vv, Q_γ):
//   ∂E/∂x_i = A Σ_c d_c e_c (X P_c)_i,
//   ∂²E/∂x_i∂x_j = A Σ_c d_c [ (X P_c)_i (X P_c)_jᵀ + e_c P_c,ij I₃ ]          (exact)
// The PSD projection keeps the first (Gauss–Newton, PSD) part and replaces the slot matrix
// S = A Σ_c d_c e_c P_c of the second by its positive part (eigenvalues clamped at 0, a 6×6
// eigenproblem); the sum is PSD, and equals the exact Hessian whenever S ⪰ 0 (e.g. at rest, and
// under uniform stretch without shear).

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "sim/rft/rft_bending_kernel.h"
#include "sim/rft/rft_patch.h"
#include "sim/types.h"

namespace weft::sim {

struct RftMembraneRest {
  std::array<RftSlotMatrix, 3> Q{RftSlotMatrix::Zero(), RftSlotMatrix::Zero(),
                                 RftSlotMatrix::Zero()};
  double area_m2 = 0.0;
  bool ok = false;  // false for a degenerate triangle or mid-edge map
};

struct RftMembraneRigidity {
  double warp_N_m = 0.0;   // Y_u
  double weft_N_m = 0.0;   // Y_v
  double shear_N_m = 0.0;  // G, per unit engineering shear strain γ
};

namespace detail {

using SlotGradients = Eigen::Matrix<double, 2, kRftPatchSlots>;  // column i = g_i, 1/m

// g_i = J⁻ᵀ dN_i with J = Σ_i X_i dN_iᵀ; false if J is singular.
inline bool rft_material_gradients(const std::array<Vec2, kRftPatchSlots>& uv,
                                   const SlotGradients& dN, SlotGradients& g) {
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int s = 0; s < kRftPatchSlots; ++s)
    J += uv[static_cast<std::size_t>(s)] * dN.col(s).transpose();
  const double det = J.determinant();
  const double size = J.cwiseAbs().maxCoeff();
  if (!(std::abs(det) > 1e-12 * size * size)) return false;
  g = J.inverse().transpose() * dN;
  return true;
}

// Parametric differentials of the barycentrics L0 = 1 − ξ − η, L1 = ξ, L2 = η.
inline Vec2 rft_barycentric_differential(int k) {
  return k == 0 ? Vec2(-1.0, -1.0) : (k == 1 ? Vec2(1.0, 0.0) : Vec2(0.0, 1.0));
}

inline void rft_add_strain_forms(const SlotGradients& g, double weight, RftMembraneRest& r) {
  const auto gu = g.row(0).transpose(), gv = g.row(1).transpose();
  r.Q[0] += weight * gu * gu.transpose();
  r.Q[1] += weight * gv * gv.transpose();
  r.Q[2] += weight * (gu * gv.transpose() + gv * gu.transpose());
}

}  // namespace detail

// RFT3: the constant-strain triangle on slots 0–2.
inline RftMembraneRest rft3_membrane_rest(const std::array<Vec2, kRftPatchSlots>& uv) {
  RftMembraneRest r;
  const Vec2 e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
  r.area_m2 = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
  detail::SlotGradients dN = detail::SlotGradients::Zero(), g;
  for (int k = 0; k < 3; ++k) dN.col(k) = detail::rft_barycentric_differential(k);
  if (!(r.area_m2 > 0.0) || !detail::rft_material_gradients(uv, dN, g)) return r;
  detail::rft_add_strain_forms(g, 1.0, r);
  r.ok = true;
  return r;
}

// RFT6: mid-edge strains of the six-node interpolation, averaged; CST strain on free edges.
inline RftMembraneRest rft6_membrane_rest(const std::array<Vec2, kRftPatchSlots>& uv,
                                          const std::array<int, 3>& opposite_slot) {
  RftMembraneRest r = rft3_membrane_rest(uv);
  if (!r.ok) return r;
  const RftMembraneRest cst = r;
  r.Q = {RftSlotMatrix::Zero(), RftSlotMatrix::Zero(), RftSlotMatrix::Zero()};
  for (int k = 0; k < 3; ++k) {
    const int p = opposite_slot[static_cast<std::size_t>(k)];
    if (p < 0) {
      for (int c = 0; c < 3; ++c)
        r.Q[static_cast<std::size_t>(c)] += cst.Q[static_cast<std::size_t>(c)] / 3.0;
      continue;
    }
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const Vec2 dLk = detail::rft_barycentric_differential(k);
    detail::SlotGradients dN = detail::SlotGradients::Zero(), g;
    dN.col(k) = 0.5 * dLk;
    dN.col(k1) = detail::rft_barycentric_differential(k1) + 0.5 * dLk;
    dN.col(k2) = detail::rft_barycentric_differential(k2) + 0.5 * dLk;
    dN.col(p) = -0.5 * dLk;
    if (!detail::rft_material_gradients(uv, dN, g)) {
      r.ok = false;
      return r;
    }
    detail::rft_add_strain_forms(g, 1.0 / 3.0, r);
  }
  return r;
}

// (ε_uu, ε_vv, γ), dimensionless.
inline Eigen::Vector3d rft_membrane_strain(const RftMembraneRest& r, const RftPatchPositions& X) {
  const RftPatchPositions Xr = rft_relative(X);
  const RftSlotMatrix gram = Xr.transpose() * Xr;  // x_i · x_j, m²
  return {0.5 * ((r.Q[0].cwiseProduct(gram)).sum() - 1.0),
          0.5 * ((r.Q[1].cwiseProduct(gram)).sum() - 1.0), 0.5 * (r.Q[2].cwiseProduct(gram)).sum()};
}

inline Eigen::Vector3d rft_membrane_diagonal(const RftMembraneRigidity& D) {
  return {D.warp_N_m, D.weft_N_m, D.shear_N_m};
}

// E = ½ A (Y_u ε_uu² + Y_v ε_vv² + G γ²), J.
inline double rft_membrane_energy(const RftMembraneRest& r, const RftMembraneRigidity& D,
                                  const RftPatchPositions& X) {
  const Eigen::Vector3d e = rft_membrane_strain(r, X);
  return 0.5 * r.area_m2 * e.cwiseProduct(e).dot(rft_membrane_diagonal(D));
}

// ∂E/∂x_i (N), as columns.
inline RftPatchGradient rft_membrane_gradient(const RftMembraneRest& r,
                                              const RftMembraneRigidity& D,
                                              const RftPatchPositions& X) {
  const Eigen::Vector3d e = rft_membrane_strain(r, X), d = rft_membrane_diagonal(D);
  RftSlotMatrix W = RftSlotMatrix::Zero();
  for (int c = 0; c < 3; ++c) W += d[c] * e[c] * r.Q[static_cast<std::size_t>(c)];
  return r.area_m2 * rft_relative(X) * W;
}

// ∂²E/∂x² (N/m), 18×18 in slot order (DOF 3i + c), exact or PSD-projected (header comment).
// Rows and columns of unused slots are zero.
inline RftPatchHessian rft_membrane_hessian(const RftMembraneRest& r, const RftMembraneRigidity& D,
                                            const RftPatchPositions& X, bool project_psd) {
  const Eigen::Vector3d e = rft_membrane_strain(r, X), d = rft_membrane_diagonal(D);
  RftPatchHessian H = RftPatchHessian::Zero();
  RftSlotMatrix S = RftSlotMatrix::Zero();
  for (int c = 0; c < 3; ++c) {
    const RftPatchGradient de =
        rft_relative(X) * r.Q[static_cast<std::size_t>(c)];  // ∂ε_c/∂x_i as columns
    const Eigen::Map<const Eigen::Matrix<double, 3 * kRftPatchSlots, 1>> v(de.data());
    H += (r.area_m2 * d[c]) * v * v.transpose();
    S += (r.area_m2 * d[c] * e[c]) * r.Q[static_cast<std::size_t>(c)];
  }
  if (project_psd) {
    Eigen::SelfAdjointEigenSolver<RftSlotMatrix> eig(S);
    S = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
        eig.eigenvectors().transpose();
  }
  for (int i = 0; i < kRftPatchSlots; ++i)
    for (int j = 0; j < kRftPatchSlots; ++j)
      H.block<3, 3>(3 * i, 3 * j).diagonal().array() += S(i, j);
  return H;
}

}  // namespace weft::sim
