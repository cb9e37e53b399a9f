#pragma once
// RFT bending (rft_bending_kernel.h) as a ForceTerm: one element per triangle, its stencil the
// triangle's patch (rft_patch.h, 3–6 vertices). The energy is quadratic in the positions, so
// element_stiffness is its exact, constant and PSD Hessian (seed 002 eq. 13) whether projected
// or not.

#include <vector>

#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"
#include "sim/rft/rft_bending_kernel.h"
#include "sim/rft/rft_patch.h"

namespace weft::sim {

class RftBending final : public ForceTerm {
 public:
  // One element per given patch (make_rft_patches(mesh), or a subset of it). Throws
  // std::invalid_argument naming the field for a negative or non-finite rigidity, and naming
  // the triangle for a degenerate patch.
  RftBending(const ClothMesh& mesh, const Material& material, std::vector<RftPatch> patches);

  std::string describe() const override;
  std::size_t element_count() const override { return m_patches.size(); }
  int stencil_size(std::size_t e) const override { return m_patches[e].size; }
  void stencil(std::size_t e, Index* vertices) const override;
  double energy(const Matrix3X& x) const override;
  void add_forces(const Matrix3X& x, Matrix3X& f) const override;
  void element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                         bool project_psd) const override;
  void add_stiffness_row_bound(Eigen::VectorXd& bound) const override;

  const std::vector<RftPatch>& patches() const { return m_patches; }
  const std::vector<RftBendingRest>& rest() const { return m_rest; }
  const RftBendingRigidity& rigidity() const { return m_rigidity; }

 private:
  std::vector<RftPatch> m_patches;
  std::vector<RftBendingRest> m_rest;
  RftBendingRigidity m_rigidity;
};

}  // namespace weft::sim
