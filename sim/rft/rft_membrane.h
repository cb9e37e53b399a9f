#pragma once
// RFT3/RFT6 membrane (rft_membrane_kernel.h) as a ForceTerm: one element per triangle; the
// stencil is the triangle (RFT3) or its patch (RFT6, rft_patch.h, 3–6 vertices).
// element_stiffness is the exact Hessian, or its PSD projection described in the kernel header.

#include <vector>

#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"
#include "sim/rft/rft.h"
#include "sim/rft/rft_membrane_kernel.h"
#include "sim/rft/rft_patch.h"

namespace weft::sim {

class RftMembraneTerm final : public ForceTerm {
 public:
  // One element per given patch (make_rft_patches(mesh), or a subset); RFT3 uses only each
  // patch's triangle. Throws as RftBending.
  RftMembraneTerm(const ClothMesh& mesh, const Material& material, RftMembrane kind,
                  std::vector<RftPatch> patches);

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
  const std::vector<RftMembraneRest>& rest() const { return m_rest; }

 private:
  RftMembrane m_kind;
  std::vector<RftPatch> m_patches;  // RFT3: trimmed to the triangle (size 3)
  std::vector<RftMembraneRest> m_rest;
  RftMembraneRigidity m_rigidity;
  Matrix3X m_rest_positions;  // for the rest stiffness bound
};

}  // namespace weft::sim
