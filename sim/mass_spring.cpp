#include "sim/mass_spring.h"

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "base/check.h"
#include "sim/collision/self_intersection.h"  // unique_edges
#include "sim/continuum/hinge_bending.h"
#include "sim/energies/bend_angle.h"
#include "sim/energies/spring.h"
#include "sim/energies/spring_hessian.h"

namespace weft::sim {
namespace {

// Width of cloth an edge stands for: half a cell of `spacing` (m) across the edge for each of
// the `cells` kept cells beside it — a whole cell inside, half a cell on a free edge.
double tributary_width(int cells, double spacing) { return 0.5 * spacing * cells; }

double rest_length(const ClothMesh& mesh, Index a, Index b) {
  return (mesh.material_coords[b] - mesh.material_coords[a]).norm();
}

// Springs along the edges of a triangle mesh (no grid): edge e of material length L at angle θ
// to the warp gets k = Y(θ) · Σ A_t / L² over the triangles t beside it, with
// Y(θ) = Y_warp cos²θ + Y_weft sin²θ (van Gelder 1998, "Approximate simulation of elastic
// membranes by triangulated spring meshes", made anisotropic). Approximate: springs on
// irregular triangles cannot reproduce given stretch and shear rigidities exactly; the shear
// rigidity is not used (docs/meshes.md). Baraff–Witkin is the accurate model on such a mesh.
std::vector<Spring> triangle_edge_springs(const ClothMesh& mesh, const Material& m) {
  std::map<std::array<Index, 2>, double> area_beside;  // edge (min, max) → Σ A_t
  for (const auto& t : mesh.faces) {
    const Vec2 p = mesh.material_coords[t[1]] - mesh.material_coords[t[0]];
    const Vec2 q = mesh.material_coords[t[2]] - mesh.material_coords[t[0]];
    const double area = 0.5 * std::abs(p.x() * q.y() - p.y() * q.x());
    for (int k = 0; k < 3; ++k) {
      const Index a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      area_beside[{std::min(a, b), std::max(a, b)}] += area;
    }
  }
  std::vector<Spring> springs;
  for (const auto& [e, area] : area_beside) {
    const Vec2 d = mesh.material_coords[e[1]] - mesh.material_coords[e[0]];
    const double L2 = d.squaredNorm();
    const double Y = (m.stretch_warp_N_m * d.x() * d.x() + m.stretch_weft_N_m * d.y() * d.y()) / L2;
    springs.push_back({e[0], e[1], std::sqrt(L2), Y * area / L2,
                       d.x() * d.x() >= d.y() * d.y() ? SpringKind::warp : SpringKind::weft});
  }
  return springs;
}

}  // namespace

namespace {

// A warp/weft grid's cell sizes and the width of cloth each of its edges stands for.
struct GridCells {
  const ClothMesh& mesh;
  double hu, hv;
  explicit GridCells(const ClothMesh& m)
      : mesh(m),
        hu(rest_length(m, m.index(0, 0), m.index(1, 0))),
        hv(rest_length(m, m.index(0, 0), m.index(0, 1))) {}
  // An edge exists when a kept cell has it as a side (ClothMesh); its tributary width comes
  // from the kept cells beside it.
  double warp_width(Index i, Index j) const { return tributary_width(mesh.warp_edge_cells(i, j), hv); }
  double weft_width(Index i, Index j) const { return tributary_width(mesh.weft_edge_cells(i, j), hu); }
};

// The springs of one direction's edges: rigidity y (N/m, the part the shear diagonals do not
// carry), or `law` less the diagonals' linear part `diagonal_N_m` when the direction has one.
// `edge(i, j)` gives an edge's end vertices, rest length and width, or none.
template <class Edges>
void add_direction_springs(const Edges& edges, double y, const std::optional<StretchLaw>& law,
                           double diagonal_N_m, SpringKind kind, std::vector<Spring>& springs,
                           std::vector<StretchLaw>& laws) {
  int index = -1;
  if (law) {
    laws.push_back(law->minus_linear(diagonal_N_m));
    index = static_cast<int>(laws.size()) - 1;
  }
  edges([&](Index a, Index b, double l, double w) {
    springs.push_back({a, b, l, y * w / l, kind, index, index < 0 ? 0.0 : w});
  });
}

// Structural springs on the grid's warp and weft edges, then shear springs on both diagonals.
std::shared_ptr<SpringTerm> grid_springs(const GridCells& g, const Material& m, bool structural) {
  const ClothMesh& mesh = g.mesh;
  const double hu = g.hu, hv = g.hv, G = m.shear_N_m;
  // Part of the stretch rigidity carried by the shear diagonals, taken off the edges.
  const double du = G * (hu * hu) / (hv * hv), dv = G * (hv * hv) / (hu * hu);
  const double yu = m.stretch_warp_N_m - du, yv = m.stretch_weft_N_m - dv;
  if (structural && (yu <= 0.0 || yv <= 0.0))
    throw MaterialError(
        "shear rigidity " + std::to_string(G) + " N/m is too large for the stretch rigidities at "
        "this cell aspect ratio (the shear springs alone would exceed the stretch stiffness)");
  std::vector<Spring> springs;
  std::vector<StretchLaw> laws;
  if (structural) {
    add_direction_springs([&](auto add) {
      for (Index j = 0; j < mesh.nv; ++j)
        for (Index i = 0; i + 1 < mesh.nu; ++i)
          if (mesh.warp_edge_cells(i, j) > 0) add(mesh.index(i, j), mesh.index(i + 1, j), hu, g.warp_width(i, j));
    }, yu, m.stretch_law_warp, du, SpringKind::warp, springs, laws);
    add_direction_springs([&](auto add) {
      for (Index j = 0; j + 1 < mesh.nv; ++j)
        for (Index i = 0; i < mesh.nu; ++i)
          if (mesh.weft_edge_cells(i, j) > 0) add(mesh.index(i, j), mesh.index(i, j + 1), hv, g.weft_width(i, j));
    }, yv, m.stretch_law_weft, dv, SpringKind::weft, springs, laws);
  }
  const double d = std::hypot(hu, hv);
  const double k_shear = G * d * d / (2.0 * hu * hv);
  if (k_shear > 0.0) {
    for (const auto& q : mesh.quads) {
      springs.push_back({q[0], q[2], d, k_shear, SpringKind::shear});
      springs.push_back({q[1], q[3], d, k_shear, SpringKind::shear});
    }
  }
  return std::make_shared<SpringTerm>(std::move(springs), std::move(laws));
}

// Angular bending stencils along warp and weft lines, where both of a stencil's edges exist,
// each standing for the mean width of the two.
std::shared_ptr<AngularBendingTerm> grid_bends(const GridCells& g, const Material& m,
                                               bool in_time_step) {
  const ClothMesh& mesh = g.mesh;
  const double hu = g.hu, hv = g.hv;
  std::vector<AngularSpring> bends;
  std::vector<BendingLaw> laws;
  const int warp_law = m.bend_law_warp ? (laws.push_back(*m.bend_law_warp), 0) : -1;
  const int weft_law =
      m.bend_law_weft ? (laws.push_back(*m.bend_law_weft), static_cast<int>(laws.size()) - 1) : -1;
  if (m.bend_warp_Nm > 0.0) {
    for (Index j = 0; j < mesh.nv; ++j)
      for (Index i = 1; i + 1 < mesh.nu; ++i)
        if (mesh.warp_edge_cells(i - 1, j) > 0 && mesh.warp_edge_cells(i, j) > 0) {
          const double w = 0.5 * (g.warp_width(i - 1, j) + g.warp_width(i, j));
          bends.push_back({mesh.index(i - 1, j), mesh.index(i, j), mesh.index(i + 1, j), 0.0,
                           m.bend_warp_Nm * w / hu, hu, w, warp_law});
        }
  }
  if (m.bend_weft_Nm > 0.0) {
    for (Index j = 1; j + 1 < mesh.nv; ++j)
      for (Index i = 0; i < mesh.nu; ++i)
        if (mesh.weft_edge_cells(i, j - 1) > 0 && mesh.weft_edge_cells(i, j) > 0) {
          const double w = 0.5 * (g.weft_width(i, j - 1) + g.weft_width(i, j));
          bends.push_back({mesh.index(i, j - 1), mesh.index(i, j), mesh.index(i, j + 1), 0.0,
                           m.bend_weft_Nm * w / hv, hv, w, weft_law});
        }
  }
  // Rest angles from the rest shape (zero for a flat grid, kept general).
  for (auto& b : bends) {
    const Vec3 x0 = vertex(mesh.rest_positions, b.v0), x1 = vertex(mesh.rest_positions, b.v1);
    b.rest_angle = turning_angle(x1 - x0, vertex(mesh.rest_positions, b.v2) - x1);
  }
  return std::make_shared<AngularBendingTerm>(std::move(bends), std::move(laws), in_time_step);
}

}  // namespace

MassSpringModel::MassSpringModel(const ClothMesh& mesh, const Material& m, bool structural_springs,
                                 bool bending_in_time_step) {
  if (!mesh.has_grid()) {
    std::vector<Spring> springs;
    if (structural_springs) springs = triangle_edge_springs(mesh, m);
    m_springs = std::make_shared<SpringTerm>(std::move(springs));
    // Bending across each edge: the dihedral hinges of the continuum model (hinge_bending.h).
    if (m.bend_warp_Nm > 0.0 || m.bend_weft_Nm > 0.0) m_hinges = std::make_shared<HingeBending>(mesh, m);
    return;
  }
  const GridCells cells(mesh);
  m_springs = grid_springs(cells, m, structural_springs);
  m_bends = grid_bends(cells, m, bending_in_time_step);
}

ForceTerms MassSpringModel::terms() const {
  ForceTerms terms;
  if (!m_springs->springs().empty()) terms.push_back(m_springs);
  if (!m_bends->bends().empty()) terms.push_back(m_bends);
  if (m_hinges) terms.push_back(m_hinges);
  return terms;
}

void MassSpringModel::add_forces(const Matrix3X& x, Matrix3X& f) const {
  m_springs->add_forces(x, f);
  m_bends->add_forces(x, f);
  if (m_hinges) m_hinges->add_forces(x, f);
}

double MassSpringModel::energy(const Matrix3X& x) const {
  return m_springs->energy(x) + m_bends->energy(x) + (m_hinges ? m_hinges->energy(x) : 0.0);
}

Eigen::VectorXd MassSpringModel::stiffness_row_bound(Index vertex_count) const {
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(vertex_count);
  m_springs->add_stiffness_row_bound(bound);
  m_bends->add_stiffness_row_bound(bound);
  if (m_hinges) m_hinges->add_stiffness_row_bound(bound);
  return bound;
}

std::string SpringTerm::describe() const {
  long warp_weft = 0, shear = 0;
  for (const Spring& s : m_springs) (s.kind == SpringKind::shear ? shear : warp_weft) += 1;
  std::string out;
  if (warp_weft > 0) out += std::to_string(warp_weft) + " warp/weft springs";
  if (shear > 0) out += (out.empty() ? "" : ", ") + std::to_string(shear) + " shear springs";
  return out;
}

SpringTerm::SpringTerm(std::vector<Spring> springs, std::vector<StretchLaw> laws)
    : m_springs(std::move(springs)), m_laws(std::move(laws)) {
  for (const Spring& s : m_springs)
    WEFT_CHECK(s.law >= -1 && s.law < static_cast<int>(m_laws.size()),
               "SpringTerm: stretch law " + std::to_string(s.law) + " of " +
                   std::to_string(m_laws.size()));
}

std::pair<double, double> SpringTerm::law_force(const Matrix3X& x, const Spring& s) const {
  const StretchLaw& law = m_laws[static_cast<std::size_t>(s.law)];
  const double strain = (vertex(x, s.b) - vertex(x, s.a)).norm() / s.rest_m - 1.0;
  return {s.width_m * law.tension(strain), s.width_m / s.rest_m * law.stiffness(strain)};
}

Mat3 SpringTerm::pair_stiffness(const Matrix3X& x, std::size_t e, bool project_psd) const {
  const Spring& s = m_springs[e];
  if (s.law >= 0) {
    const auto [force, axial] = law_force(x, s);
    return spring_hessian_b_from_force(vertex(x, s.a), vertex(x, s.b), force, axial, project_psd);
  }
  return project_psd ? spring_hessian_b_projected(vertex(x, s.a), vertex(x, s.b), s.rest_m, s.k_N_m)
                     : spring_hessian_b(vertex(x, s.a), vertex(x, s.b), s.rest_m, s.k_N_m);
}

double SpringTerm::energy(const Matrix3X& x) const {
  double e = 0.0;
  for (const Spring& s : m_springs) {
    if (s.law < 0) {
      e += spring_energy(vertex(x, s.a), vertex(x, s.b), s.rest_m, s.k_N_m);
      continue;
    }
    const double strain = (vertex(x, s.b) - vertex(x, s.a)).norm() / s.rest_m - 1.0;
    e += s.width_m * s.rest_m * m_laws[static_cast<std::size_t>(s.law)].energy_density(strain);
  }
  return e;
}

void SpringTerm::add_forces(const Matrix3X& x, Matrix3X& f) const {
  for (const Spring& s : m_springs) {
    const Vec3 g = s.law < 0 ? spring_gradient_b(vertex(x, s.a), vertex(x, s.b), s.rest_m, s.k_N_m)
                             : spring_gradient_b_from_force(vertex(x, s.a), vertex(x, s.b),
                                                            law_force(x, s).first);
    f.row(s.a) += g.transpose();
    f.row(s.b) -= g.transpose();
  }
}

void SpringTerm::add_stiffness_row_bound(Eigen::VectorXd& bound) const {
  for (const Spring& s : m_springs) {
    bound[s.a] += 2.0 * s.k_N_m;
    bound[s.b] += 2.0 * s.k_N_m;
  }
}

std::string AngularBendingTerm::describe() const {
  return std::to_string(m_bends.size()) + " bending stencils" +
         (m_in_time_step ? " (stiffness in the step's matrix)" : "");
}

void AngularBendingTerm::stencil(std::size_t e, Index* vertices) const {
  vertices[0] = m_bends[e].v0;
  vertices[1] = m_bends[e].v1;
  vertices[2] = m_bends[e].v2;
}

AngularBendingTerm::AngularBendingTerm(std::vector<AngularSpring> bends, std::vector<BendingLaw> laws,
                                       bool in_time_step)
    : m_bends(std::move(bends)), m_laws(std::move(laws)), m_in_time_step(in_time_step) {
  for (const AngularSpring& b : m_bends)
    WEFT_CHECK(b.law >= -1 && b.law < static_cast<int>(m_laws.size()),
               "AngularBendingTerm: bending law " + std::to_string(b.law) + " of " +
                   std::to_string(m_laws.size()));
}

AngleEnergySlope AngularBendingTerm::slope(const AngularSpring& b, double theta) const {
  if (b.law < 0) return linear_angle_slope(theta, b.rest_angle, b.k_Nm);
  const BendingLaw& law = m_laws[static_cast<std::size_t>(b.law)];
  const double l = b.rest_l_m, kappa = (theta - b.rest_angle) / l;
  return {b.width_m * law.moment(kappa), b.width_m / l * law.stiffness(kappa),
          b.width_m / l * law.initial_rigidity()};
}

double AngularBendingTerm::energy(const Matrix3X& x) const {
  double e = 0.0;
  for (const AngularSpring& b : m_bends) {
    if (b.law < 0) {
      e += bend_angle_energy(vertex(x, b.v0), vertex(x, b.v1), vertex(x, b.v2), b.rest_angle, b.k_Nm);
      continue;
    }
    const Vec3 x1 = vertex(x, b.v1);
    const double theta = turning_angle(x1 - vertex(x, b.v0), vertex(x, b.v2) - x1);
    const double kappa = (theta - b.rest_angle) / b.rest_l_m;
    e += b.width_m * b.rest_l_m *
         m_laws[static_cast<std::size_t>(b.law)].energy_density(kappa);
  }
  return e;
}

void AngularBendingTerm::add_forces(const Matrix3X& x, Matrix3X& f) const {
  for (const AngularSpring& b : m_bends) {
    const auto g = bend_angle_gradient(vertex(x, b.v0), vertex(x, b.v1), vertex(x, b.v2),
                                       b.rest_angle, [&](double theta) { return slope(b, theta); });
    f.row(b.v0) -= g[0].transpose();
    f.row(b.v1) -= g[1].transpose();
    f.row(b.v2) -= g[2].transpose();
  }
}

void AngularBendingTerm::element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                                           bool project_psd) const {
  const AngularSpring& b = m_bends[e];
  Eigen::Matrix<double, 9, 9> H;
  bend_angle_hessian(vertex(x, b.v0), vertex(x, b.v1), vertex(x, b.v2), b.rest_angle,
                     [&](double theta) { return slope(b, theta); }, project_psd, H);
  K = H;
}

void AngularBendingTerm::time_step_stiffness(const Matrix3X& x, std::size_t e,
                                             ElementMatrix& K) const {
  const AngularSpring& b = m_bends[e];
  const Vec3 x0 = vertex(x, b.v0), x1 = vertex(x, b.v1), x2 = vertex(x, b.v2);
  // A linear stencil's stiffness is k_Nm at every angle: no angle to compute.
  const double k =
      b.law < 0 ? b.k_Nm : std::max(0.0, slope(b, turning_angle(x1 - x0, x2 - x1)).d2E);
  const double c = k / (b.rest_l_m * b.rest_l_m);
  Mat3 across = Mat3::Identity();  // P = I − t tᵀ; all of I for a collapsed stencil
  const Vec3 chord = x2 - x0;
  if (const double length = chord.norm(); length > 0.0) {
    const Vec3 t = chord / length;
    across -= t * t.transpose();
  }
  constexpr double w[3] = {1.0, -2.0, 1.0};
  K.resize(9, 9);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) K.block<3, 3>(3 * i, 3 * j) = (c * w[i] * w[j]) * across;
}

void AngularBendingTerm::add_stiffness_row_bound(Eigen::VectorXd& bound) const {
  for (const AngularSpring& b : m_bends) {
    const double k = b.law < 0 ? b.k_Nm
                               : b.width_m / b.rest_l_m *
                                     m_laws[static_cast<std::size_t>(b.law)].initial_rigidity();
    const double c = k / (b.rest_l_m * b.rest_l_m);
    bound[b.v0] += 4.0 * c;
    bound[b.v1] += 8.0 * c;
    bound[b.v2] += 4.0 * c;
  }
}

}  // namespace weft::sim
