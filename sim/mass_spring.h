#pragma once
// Mass-spring cloth on a warp/weft quad grid (seeds 003 and 004):
//   structural springs on warp and weft edges, shear springs on both diagonals of each quad,
//   angular bending springs on skip-one stencils along warp and weft lines.
// Stiffnesses come from per-width material rigidities and the rest geometry, so that refining
// the grid does not change the behaviour (seed 004: k_i ∝ 1/l_i).

#include <vector>

#include "sim/grid.h"
#include "sim/material.h"
#include "sim/types.h"

namespace weft::sim {

enum class SpringKind { warp, weft, shear };

struct Spring {
  Index a, b;
  double rest_m;
  double k_N_m;
  SpringKind kind;
};

struct AngularSpring {  // vertices x0, x1, x2 along a warp or weft line
  Index v0, v1, v2;
  double rest_angle;    // radians (0 on a flat grid)
  double k_Nm;          // N·m per radian²
  double rest_l_m;      // mean rest length of the two edges
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
  MassSpringModel(const ClothMesh& mesh, const Material& material, bool structural_springs = true);
  MassSpringModel() = default;

  // f += −∇E(x), forces in N.
  void add_forces(const Matrix3X& x, Matrix3X& f) const;
  // Elastic energy, J.
  double energy(const Matrix3X& x) const;
  // Per-vertex upper bound on the rows of the rest stiffness matrix (Gershgorin), N/m: with
  // masses m, the largest eigenvalue of M⁻¹K is at most max_i bound_i / m_i.
  Eigen::VectorXd stiffness_row_bound(Index vertex_count) const;

  const std::vector<Spring>& springs() const { return m_springs; }
  const std::vector<AngularSpring>& bends() const { return m_bends; }

 private:
  std::vector<Spring> m_springs;  // warp and weft edges (if any), then shear diagonals
  std::vector<AngularSpring> m_bends;
};

}  // namespace weft::sim
