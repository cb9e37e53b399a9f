#include "sim/rft/rft_membrane.h"

#include <sstream>
#include <stdexcept>
#include <utility>

namespace weft::sim {

RftMembraneTerm::RftMembraneTerm(const ClothMesh& mesh, const Material& material, RftMembrane kind,
                                 std::vector<RftPatch> patches)
    : m_kind(kind), m_patches(std::move(patches)), m_rest_positions(mesh.rest_positions) {
  check_rft_rigidity(material.stretch_warp_N_m, "material.stretch_warp_N_m");
  check_rft_rigidity(material.stretch_weft_N_m, "material.stretch_weft_N_m");
  check_rft_rigidity(material.shear_N_m, "material.shear_N_m");
  m_rigidity = {material.stretch_warp_N_m, material.stretch_weft_N_m, material.shear_N_m};
  m_rest.reserve(m_patches.size());
  for (RftPatch& p : m_patches) {
    if (kind == RftMembrane::three_node) {
      p.size = 3;  // the constant-strain triangle needs no neighbours
      p.opposite_slot = {-1, -1, -1};
    }
    const auto uv = rft_patch_material_coords(mesh, p);
    m_rest.push_back(kind == RftMembrane::three_node ? rft3_membrane_rest(uv)
                                                     : rft6_membrane_rest(uv, p.opposite_slot));
    if (!m_rest.back().ok)
      throw std::invalid_argument("RFT membrane: triangle " + std::to_string(p.triangle) +
                                  " is degenerate (zero area, or a singular mid-edge map)");
  }
}

std::string RftMembraneTerm::describe() const {
  std::ostringstream out;
  out << (m_kind == RftMembrane::three_node ? "RFT3 membrane (constant-strain triangles)"
                                            : "RFT6 membrane (six-node mid-edge strains)")
      << " on " << m_patches.size() << " triangles";
  return out.str();
}

void RftMembraneTerm::stencil(std::size_t e, Index* vertices) const {
  for (int s = 0; s < m_patches[e].size; ++s)
    vertices[s] = m_patches[e].vertices[static_cast<std::size_t>(s)];
}

double RftMembraneTerm::energy(const Matrix3X& x) const {
  double sum = 0.0;
  for (std::size_t e = 0; e < m_patches.size(); ++e)
    sum += rft_membrane_energy(m_rest[e], m_rigidity, rft_gather(x, m_patches[e]));
  return sum;
}

void RftMembraneTerm::add_forces(const Matrix3X& x, Matrix3X& f) const {
  for (std::size_t e = 0; e < m_patches.size(); ++e)
    rft_scatter_minus(rft_membrane_gradient(m_rest[e], m_rigidity, rft_gather(x, m_patches[e])),
                      m_patches[e], f);
}

void RftMembraneTerm::element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                                        bool project_psd) const {
  const int n = m_patches[e].size;
  K = rft_membrane_hessian(m_rest[e], m_rigidity, rft_gather(x, m_patches[e]), project_psd)
          .topLeftCorner(3 * n, 3 * n);
}

void RftMembraneTerm::add_stiffness_row_bound(Eigen::VectorXd& bound) const {
  add_row_bound_from_stiffness(*this, m_rest_positions, bound);
}

std::unique_ptr<ForceTerm> make_rft_membrane(const ClothMesh& mesh, const Material& material,
                                             RftMembrane kind) {
  return std::make_unique<RftMembraneTerm>(mesh, material, kind, make_rft_patches(mesh));
}

}  // namespace weft::sim
