#include "sim/rft/rft_bending.h"

#include <sstream>
#include <stdexcept>
#include <utility>

#include "sim/rft/rft.h"

namespace weft::sim {

RftBending::RftBending(const ClothMesh& mesh, const Material& material,
                       std::vector<RftPatch> patches)
    : m_patches(std::move(patches)) {
  check_rft_rigidity(material.bend_warp_Nm, "material.bend_warp_Nm");
  check_rft_rigidity(material.bend_weft_Nm, "material.bend_weft_Nm");
  m_rigidity = rft_bending_rigidity(material.bend_warp_Nm, material.bend_weft_Nm);
  m_rest.reserve(m_patches.size());
  for (const RftPatch& p : m_patches) {
    m_rest.push_back(rft_bending_rest(rft_patch_material_coords(mesh, p), p.opposite_slot));
    if (!m_rest.back().ok)
      throw std::invalid_argument("RFT bending: triangle " + std::to_string(p.triangle) +
                                  " has a degenerate patch (zero area, or its " +
                                  std::to_string(p.size) +
                                  " vertices admit no unique quadratic fit)");
  }
}

std::string RftBending::describe() const {
  std::size_t boundary = 0;
  for (const RftPatch& p : m_patches) boundary += p.size < 6 ? 1 : 0;
  std::ostringstream out;
  out << "rotation-free-triangle bending (six-node patches, constant stiffness) on "
      << m_patches.size() << " triangles (" << boundary << " on a free edge)";
  return out.str();
}

void RftBending::stencil(std::size_t e, Index* vertices) const {
  for (int s = 0; s < m_patches[e].size; ++s)
    vertices[s] = m_patches[e].vertices[static_cast<std::size_t>(s)];
}

double RftBending::energy(const Matrix3X& x) const {
  double sum = 0.0;
  for (std::size_t e = 0; e < m_patches.size(); ++e)
    sum += rft_bending_energy(m_rest[e], m_rigidity, rft_gather(x, m_patches[e]));
  return sum;
}

void RftBending::add_forces(const Matrix3X& x, Matrix3X& f) const {
  for (std::size_t e = 0; e < m_patches.size(); ++e)
    rft_scatter_minus(rft_bending_gradient(m_rest[e], m_rigidity, rft_gather(x, m_patches[e])),
                      m_patches[e], f);
}

void RftBending::element_stiffness(const Matrix3X& /*x*/, std::size_t e, ElementMatrix& K,
                                   bool /*project_psd*/) const {
  const int n = m_patches[e].size;
  const RftSlotMatrix S = rft_bending_slot_stiffness(m_rest[e], m_rigidity);
  K.setZero(3 * n, 3 * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) K.block(3 * i, 3 * j, 3, 3).diagonal().setConstant(S(i, j));
}

void RftBending::add_stiffness_row_bound(Eigen::VectorXd& bound) const {
  // K = S ⊗ I₃: each 3-row of slot i sums to Σ_j |S_ij|.
  for (std::size_t e = 0; e < m_patches.size(); ++e) {
    const RftSlotMatrix S = rft_bending_slot_stiffness(m_rest[e], m_rigidity);
    for (int i = 0; i < m_patches[e].size; ++i)
      bound[m_patches[e].vertices[static_cast<std::size_t>(i)]] += S.row(i).cwiseAbs().sum();
  }
}

std::unique_ptr<ForceTerm> make_rft_bending(const ClothMesh& mesh, const Material& material) {
  return std::make_unique<RftBending>(mesh, material, make_rft_patches(mesh));
}

}  // namespace weft::sim
