#pragma once
// Mass-spring cloth on a warp/weft quad grid (seeds 003 and 004):
//   structural springs on warp and weft edges, shear springs on both diagonals of each quad,
//   angular bending springs on skip-one stencils along warp and weft lines.
// Stiffnesses come from per-width material rigidities and the rest geometry, so that refining
// the grid does not change the behaviour (seed 004: k_i ∝ 1/l_i).
// The springs and the angular bending are two ForceTerms (sim/force_term.h), SpringTerm and
// AngularBendingTerm, which a System steps like any other; MassSpringModel builds them.
// On a triangle mesh without a grid (a mesh file): springs along every triangle edge and
// dihedral hinges across every interior edge instead (mass_spring.cpp, docs/meshes.md).

#include <memory>
#include <string>
#include <vector>

#include "sim/material/bending_law.h"
#include "sim/energies/bend_angle.h"
#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"
#include "sim/material/stretch_law.h"
#include "sim/types.h"

namespace weft::sim {

enum class SpringKind { warp, weft, shear };

struct Spring {
  Index a, b;
  double rest_m;
  double k_N_m;          // N/m: the linear law's stiffness, or a stretch law's at rest (w/l T'(0))
  SpringKind kind;
  int law = -1;          // index of its StretchLaw in the term's laws; −1: linear, k_N_m
  double width_m = 0.0;  // with a law: the width of cloth the edge stands for, w
};

struct AngularSpring {  // vertices x0, x1, x2 along a warp or weft line
  Index v0, v1, v2;
  double rest_angle;    // radians (0 on a flat grid)
  double k_Nm;          // N·m per radian² (the linear law: B w / l̄)
  double rest_l_m;      // mean rest length of the two edges, l̄
  double width_m = 0.0; // the width of cloth the line stands for, w
  int law = -1;         // index of its BendingLaw in the term's laws; −1: linear, k_Nm
};

// Linear springs (sim/energies/spring.h): ½ k (|x_b − x_a| − l)² each, or with a nonlinear
// stretch law T(ε) (sim/material/stretch_law.h) the edge's share of ∫ W(ε) dA, w l W(ε) for
// ε = |x_b − x_a|/l − 1, whose force along the edge is w T(ε). The row bound is the one at rest,
// with the law's initial stiffness: a stiffening law is stiffer when stretched.
class SpringTerm final : public PairForceTerm {
 public:
  // Each spring's law indexes `laws` (or is −1: linear); a bad index is a bug (WEFT_CHECK).
  explicit SpringTerm(std::vector<Spring> springs, std::vector<StretchLaw> laws = {});
  // "144 warp/weft springs, 128 shear springs" (the kinds present).
  std::string describe() const override;
  std::size_t element_count() const override { return m_springs.size(); }
  std::pair<Index, Index> pair(std::size_t e) const override {
    return {m_springs[e].a, m_springs[e].b};
  }
  Mat3 pair_stiffness(const Matrix3X& x, std::size_t e, bool project_psd) const override;
  double energy(const Matrix3X& x) const override;
  void add_forces(const Matrix3X& x, Matrix3X& f) const override;
  // A spring's 6×6 Hessian at rest is k [I −I; −I I] ⊗ d̂d̂ᵀ: each row of blocks sums to 2k.
  void add_stiffness_row_bound(Eigen::VectorXd& bound) const override;
  const std::vector<Spring>& springs() const { return m_springs; }

 private:
  // A law spring's force along it f = dE/d|d| (N) and axial stiffness d²E/d|d|² (N/m) at x.
  std::pair<double, double> law_force(const Matrix3X& x, const Spring& s) const;
  std::vector<Spring> m_springs;
  std::vector<StretchLaw> m_laws;
};

// Angular bending springs (sim/energies/bend_angle.h) along warp and weft lines: ½ k (θ − θ0)²
// each, or with a nonlinear bending law M(κ) (sim/material/bending_law.h) the stencil's share of
// ∫ W(κ) dA, w l̄ W((θ − θ0) / l̄), whose slope dE/dθ = w M(κ) is the moment the stencil's
// width carries. The row bound is the near-flat one, with the law's initial rigidity.
class AngularBendingTerm final : public ForceTerm {
 public:
  // Each bend's law indexes `laws` (or is −1: linear); a bad index is a bug (WEFT_CHECK).
  // in_time_step: the stiffness enters implicit Euler's matrix (time_step_stiffness).
  explicit AngularBendingTerm(std::vector<AngularSpring> bends, std::vector<BendingLaw> laws = {},
                              bool in_time_step = false);
  std::string describe() const override;  // "7936 bending stencils"
  std::size_t element_count() const override { return m_bends.size(); }
  int stencil_size(std::size_t) const override { return 3; }
  void stencil(std::size_t e, Index* vertices) const override;
  double energy(const Matrix3X& x) const override;
  void add_forces(const Matrix3X& x, Matrix3X& f) const override;
  // By default left out of implicit Euler's matrix: the bending stays explicit in a time step
  // (its forces are small beside the springs'), which is stable while h² ω_bend² is small
  // (bending_in_time_step(), sim/simulator.cpp); static solves always use the stiffness.
  bool stiffness_in_time_step() const override { return m_in_time_step; }
  // The exact 9×9 Hessian of each stencil (bend_angle_hessian).
  void element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                         bool project_psd) const override;
  // In a time step, the near-flat Hessian: across a nearly straight line θ ≈ |P(x0 − 2x1 + x2)|/l̄
  // (P = I − t tᵀ, t the line's direction x2 − x0), so ½ k θ² has the Hessian
  // (k/l̄²)·[1 −2 1]ᵀ[1 −2 1] ⊗ P, with k the law's tangent stiffness d²E/dθ² at the current
  // angle. PSD by construction (no eigen-decomposition), exact for a straight stencil, and what
  // inextensible bending is to second order (Bergou et al. 2006, "A quadratic bending model for
  // inextensible surfaces"). The exact Hessian's indefinite part along a bent line is left out.
  void time_step_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K) const override;
  // Near flat, θ ≈ (δ0 − 2δ1 + δ2)/l across the line: Hessian (k/l²)·[1 −2 1]ᵀ[1 −2 1], whose
  // block rows sum to 4k/l² at the ends and 8k/l² in the middle.
  void add_stiffness_row_bound(Eigen::VectorXd& bound) const override;
  const std::vector<AngularSpring>& bends() const { return m_bends; }

 private:
  // The stencil's energy slope at turning angle θ.
  AngleEnergySlope slope(const AngularSpring& b, double theta) const;
  std::vector<AngularSpring> m_bends;
  std::vector<BendingLaw> m_laws;
  bool m_in_time_step = false;
};

// Stiffnesses for a cell of hu × hv metres (derivations in docs/models.md):
//   shear diagonal  k = G d² / (2 hu hv)          (pure shear γ stretches the diagonals by ±hu hv γ / d)
//   warp edge       k = (Y_u − G hu²/hv²) w / hu   (the diagonals already carry G hu²/hv² of the warp stretch)
//   bending         k = B w / l̄                   (Kass: ½ B κ² per area)
// where w is the width of cloth the edge or line stands for (half a cell on the boundary).
class MassSpringModel {
 public:
  // Without structural springs (structural_springs = false) the warp and weft edges are left
  // to an inextensibility constraint solver (seed 000: constraints on warp/weft, soft shear
  // springs, bending).
  // Springs or stencils whose stiffness would be zero (zero shear or bending rigidity) are left
  // out. The default-constructed model is empty (a continuum model's, sim/cloth_model.h).
  // bending_in_time_step: the grid's bending stiffness enters implicit Euler's matrix
  // (AngularBendingTerm::time_step_stiffness).
  MassSpringModel(const ClothMesh& mesh, const Material& material, bool structural_springs = true,
                  bool bending_in_time_step = false);
  MassSpringModel() = default;

  // The model's terms, springs then bending, each only when it has elements.
  ForceTerms terms() const;

  // f += −∇E(x), forces in N (both terms).
  void add_forces(const Matrix3X& x, Matrix3X& f) const;
  // Elastic energy, J.
  double energy(const Matrix3X& x) const;
  // Per-vertex upper bound on the rows of the rest stiffness matrix (Gershgorin), N/m: with
  // masses m, the largest eigenvalue of M⁻¹K is at most max_i bound_i / m_i.
  Eigen::VectorXd stiffness_row_bound(Index vertex_count) const;

  // Warp and weft edges (if any), then shear diagonals.
  const std::vector<Spring>& springs() const { return m_springs->springs(); }
  const std::vector<AngularSpring>& bends() const { return m_bends->bends(); }

 private:
  std::shared_ptr<const SpringTerm> m_springs = std::make_shared<SpringTerm>(std::vector<Spring>{});
  // A mesh without a grid: bending across its edges by dihedral hinges, or null.
  std::shared_ptr<const ForceTerm> m_hinges;
  std::shared_ptr<const AngularBendingTerm> m_bends =
      std::make_shared<AngularBendingTerm>(std::vector<AngularSpring>{});
};

}  // namespace weft::sim
