#pragma once
// The Baraff–Witkin membrane (stretch and shear per triangle, bw_membrane_kernel.h) as a
// ForceTerm over both triangulations of the cloth's quads at half weight
// (quad_triangulations.h).

#include <vector>

#include "sim/continuum/bw_membrane_kernel.h"
#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"

namespace weft::sim {

class BwMembrane final : public ForceTerm {
 public:
  // with_stretch = false leaves warp and weft to an inextensibility constraint (shear only).
  BwMembrane(const ClothMesh& mesh, const Material& material, bool with_stretch);

  std::string describe() const override;
  std::size_t element_count() const override { return m_triangles.size(); }
  int stencil_size(std::size_t) const override { return 3; }
  void stencil(std::size_t e, Index* vertices) const override;
  double energy(const Matrix3X& x) const override;
  void add_forces(const Matrix3X& x, Matrix3X& f) const override;
  void element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                         bool project_psd) const override;
  void add_stiffness_row_bound(Eigen::VectorXd& bound) const override;

 private:
  BwMap map(const Matrix3X& x, std::size_t e) const;

  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<BwTriangleRest> m_rest;
  BwRigidities m_k;
  Matrix3X m_rest_positions;  // for the rest stiffness bound
  bool m_grid = true;  // built on a grid's two splits (describe())
};

}  // namespace weft::sim
