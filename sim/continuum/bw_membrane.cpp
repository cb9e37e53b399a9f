#include "sim/continuum/bw_membrane.h"

#include <sstream>

#include "sim/continuum/quad_triangulations.h"

namespace weft::sim {

BwMembrane::BwMembrane(const ClothMesh& mesh, const Material& material, bool with_stretch)
    : m_rest_positions(mesh.rest_positions), m_grid(mesh.has_grid()) {
  m_k.warp_N_m = with_stretch ? material.stretch_warp_N_m : 0.0;
  m_k.weft_N_m = with_stretch ? material.stretch_weft_N_m : 0.0;
  m_k.shear_N_m = material.shear_N_m;
  // Both splits of every quad at half weight (quad_triangulations.h): the weight scales the
  // rest area, through which it enters the energy and all its derivatives.
  for (const Triangles& split : quad_triangulations(mesh)) {
    for (const auto& t : split) {
      m_triangles.push_back(t);
      BwTriangleRest rest = bw_triangle_rest(mesh.material_coords[t[0]], mesh.material_coords[t[1]],
                                             mesh.material_coords[t[2]]);
      rest.area_m2 *= split_weight(mesh);
      m_rest.push_back(rest);
    }
  }
}

std::string BwMembrane::describe() const {
  std::ostringstream out;
  out << "Baraff–Witkin "
      << (m_k.warp_N_m > 0.0 || m_k.weft_N_m > 0.0 ? "stretch and shear" : "shear") << " on "
      << m_triangles.size() << " triangles" << (m_grid ? " (both diagonals of each quad)" : "");
  return out.str();
}

void BwMembrane::stencil(std::size_t e, Index* vertices) const {
  for (int k = 0; k < 3; ++k) vertices[k] = m_triangles[e][static_cast<std::size_t>(k)];
}

BwMap BwMembrane::map(const Matrix3X& x, std::size_t e) const {
  const auto& t = m_triangles[e];
  return bw_map(m_rest[e], x.row(t[0]).transpose(), x.row(t[1]).transpose(),
                x.row(t[2]).transpose());
}

double BwMembrane::energy(const Matrix3X& x) const {
  double sum = 0.0;
  for (std::size_t e = 0; e < m_triangles.size(); ++e)
    sum += bw_membrane_energy(m_rest[e], m_k, map(x, e));
  return sum;
}

void BwMembrane::add_forces(const Matrix3X& x, Matrix3X& f) const {
  for (std::size_t e = 0; e < m_triangles.size(); ++e) {
    const Vec6 g = bw_membrane_gradient_w(m_rest[e], m_k, map(x, e));
    const BwTriangleRest& r = m_rest[e];
    for (std::size_t k = 0; k < 3; ++k)
      f.row(m_triangles[e][k]) -= (r.alpha[k] * g.head<3>() + r.beta[k] * g.tail<3>()).transpose();
  }
}

// Block (k, l) = Σ_{a,b ∈ {u,v}} coef_a(k) coef_b(l) H_ab, coef_u = α, coef_v = β.
void BwMembrane::element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                                   bool project_psd) const {
  const Mat6 H = bw_membrane_hessian_w(m_rest[e], m_k, map(x, e), project_psd);
  const BwTriangleRest& r = m_rest[e];
  K.resize(9, 9);
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t l = 0; l < 3; ++l) {
      const double ak = r.alpha[k], bk = r.beta[k], al = r.alpha[l], bl = r.beta[l];
      K.block<3, 3>(3 * static_cast<int>(k), 3 * static_cast<int>(l)) =
          ak * al * H.topLeftCorner<3, 3>() + ak * bl * H.topRightCorner<3, 3>() +
          bk * al * H.bottomLeftCorner<3, 3>() + bk * bl * H.bottomRightCorner<3, 3>();
    }
}

void BwMembrane::add_stiffness_row_bound(Eigen::VectorXd& bound) const {
  add_row_bound_from_stiffness(*this, m_rest_positions, bound);
}

}  // namespace weft::sim
