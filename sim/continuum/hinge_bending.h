#pragma once
// Bending on every interior edge of both triangulations of the cloth's quads, each at half
// weight (quad_triangulations.h; hinge_kernel.h), as a ForceTerm,
// anisotropic: an edge whose rest direction in material coordinates is t = (t_u, t_v) bends
// the cloth across it, along the normal n = (−t_v, t_u), with the rigidity
//   B(n) = B_warp n_u² + B_weft n_v²
// (the directional bending rigidity of an orthotropic sheet without twist coupling). Edges
// along the weft (n = u) thus carry the warp bending, which is how a grid bent along the warp
// bends: only those edges fold (docs/models.md).

#include <array>
#include <vector>

#include "sim/continuum/hinge_kernel.h"
#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"

namespace weft::sim {

struct Hinge {
  std::array<Index, 4> v;   // a, b (the edge), c, d (hinge_kernel.h)
  double rest_angle = 0.0;  // rad
  double k_Nm = 0.0;        // B |e|² / (A1 + A2), N·m per rad²
};

class HingeBending final : public ForceTerm {
 public:
  // Hinges with zero rigidity are left out.
  HingeBending(const ClothMesh& mesh, const Material& material);

  std::string describe() const override;
  std::size_t element_count() const override { return m_hinges.size(); }
  int stencil_size(std::size_t) const override { return 4; }
  void stencil(std::size_t e, Index* vertices) const override;
  double energy(const Matrix3X& x) const override;
  void add_forces(const Matrix3X& x, Matrix3X& f) const override;
  // Gauss–Newton k ∇θ∇θᵀ whether projected or not (hinge_kernel.h): exact at θ = θ0.
  void element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                         bool project_psd) const override;
  void add_stiffness_row_bound(Eigen::VectorXd& bound) const override;

  const std::vector<Hinge>& hinges() const { return m_hinges; }

 private:
  double angle(const Matrix3X& x, const Hinge& h) const;
  Vec12 angle_gradient(const Matrix3X& x, const Hinge& h) const;

  std::vector<Hinge> m_hinges;
  Matrix3X m_rest_positions;
  bool m_grid = true;  // built on a grid's two splits (describe())
};

}  // namespace weft::sim
