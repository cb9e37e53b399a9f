#include "sim/continuum/hinge_bending.h"

#include <map>
#include <sstream>
#include <utility>

#include "sim/continuum/hinge_kernel.h"
#include "sim/continuum/quad_triangulations.h"

namespace weft::sim {
namespace {

double triangle_area(const ClothMesh& mesh, const std::array<Index, 3>& t) {
  const Vec2 p = mesh.material_coords[t[1]] - mesh.material_coords[t[0]];
  const Vec2 q = mesh.material_coords[t[2]] - mesh.material_coords[t[0]];
  return 0.5 * std::abs(p.x() * q.y() - p.y() * q.x());
}

}  // namespace

HingeBending::HingeBending(const ClothMesh& mesh, const Material& material)
    : m_rest_positions(mesh.rest_positions), m_grid(mesh.has_grid()) {
  // Each directed triangle edge i → j with opposite k; the edge's other triangle runs j → i.
  struct Half {
    Index a, b, c;
    double area;
  };
  std::vector<std::pair<Half, Half>> pairs;
  // Hinges of each split separately, at half weight (quad_triangulations.h).
  for (const Triangles& split : quad_triangulations(mesh)) {
    std::map<std::pair<Index, Index>, Half> open;  // keyed by (min, max): deterministic order
    for (const auto& t : split) {
      const double area = triangle_area(mesh, t);
      for (int k = 0; k < 3; ++k) {
        const Half h{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)],
                     t[static_cast<std::size_t>((k + 2) % 3)], area};
        const auto key = std::minmax(h.a, h.b);
        const auto it = open.find(key);
        if (it == open.end()) {
          open.emplace(key, h);
        } else {
          pairs.emplace_back(it->second, h);
          open.erase(it);
        }
      }
    }
  }
  for (const auto& [first, second] : pairs) {
    const Vec2 t = (mesh.material_coords[first.b] - mesh.material_coords[first.a]);
    const double len2 = t.squaredNorm();
    // Normal n = (−t_v, t_u)/|t|: n_u² = t_v²/|t|², n_v² = t_u²/|t|².
    const double B =
        (material.bend_warp_Nm * t.y() * t.y() + material.bend_weft_Nm * t.x() * t.x()) / len2;
    if (B == 0.0) continue;
    Hinge h;
    h.v = {first.a, first.b, first.c, second.c};
    h.k_Nm = split_weight(mesh) * B * len2 / (first.area + second.area);
    h.rest_angle = angle(mesh.rest_positions, h);
    m_hinges.push_back(h);
  }
}

std::string HingeBending::describe() const {
  std::ostringstream out;
  out << "dihedral-angle bending on " << m_hinges.size() << " hinges" << (m_grid ? " (both diagonals of each quad)" : "");
  return out.str();
}

void HingeBending::stencil(std::size_t e, Index* vertices) const {
  for (int k = 0; k < 4; ++k) vertices[k] = m_hinges[e].v[static_cast<std::size_t>(k)];
}

double HingeBending::angle(const Matrix3X& x, const Hinge& h) const {
  return hinge_angle(x.row(h.v[0]).transpose(), x.row(h.v[1]).transpose(),
                     x.row(h.v[2]).transpose(), x.row(h.v[3]).transpose());
}

Vec12 HingeBending::angle_gradient(const Matrix3X& x, const Hinge& h) const {
  return hinge_angle_gradient(x.row(h.v[0]).transpose(), x.row(h.v[1]).transpose(),
                              x.row(h.v[2]).transpose(), x.row(h.v[3]).transpose());
}

double HingeBending::energy(const Matrix3X& x) const {
  double sum = 0.0;
  for (const Hinge& h : m_hinges) sum += hinge_energy(angle(x, h), h.rest_angle, h.k_Nm);
  return sum;
}

void HingeBending::add_forces(const Matrix3X& x, Matrix3X& f) const {
  for (const Hinge& h : m_hinges) {
    const double excess = angle(x, h) - h.rest_angle;
    const Vec12 g = h.k_Nm * excess * angle_gradient(x, h);
    for (std::size_t k = 0; k < 4; ++k)
      f.row(h.v[k]) -= g.segment<3>(3 * static_cast<int>(k)).transpose();
  }
}

void HingeBending::element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                                     bool /*project_psd*/) const {
  const Hinge& h = m_hinges[e];
  const Vec12 g = angle_gradient(x, h);
  K = h.k_Nm * g * g.transpose();
}

void HingeBending::add_stiffness_row_bound(Eigen::VectorXd& bound) const {
  add_row_bound_from_stiffness(*this, m_rest_positions, bound);
}

}  // namespace weft::sim
