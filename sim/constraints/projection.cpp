#include "sim/constraints/projection.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/collision/self_intersection.h"  // unique_edges
#include "sim/constraints/fast_projection.h"
#include "sim/constraints/inextensibility.h"
#include "sim/constraints/pairwise_projection.h"

namespace weft::sim {

std::vector<EdgeConstraint> make_edge_constraints(const ClothMesh& mesh, ConstrainedEdges which,
                                                  const Eigen::VectorXd& inv_mass) {
  std::vector<EdgeConstraint> out;
  const auto add = [&](Index a, Index b) {
    if (inv_mass[a] == 0.0 && inv_mass[b] == 0.0) return;  // both pinned: nothing to solve
    out.push_back({a, b, (mesh.material_coords[b] - mesh.material_coords[a]).norm()});
  };
  // A mesh without a grid: its triangles' edges stand in for both sets (make_projector refuses
  // warp_weft on it; the strain diagnostic measures them).
  if (!mesh.has_grid()) {
    for (const auto& e : unique_edges(mesh.faces)) add(e[0], e[1]);
    return out;
  }
  // The edges of the kept cells only (ClothMesh).
  for (Index j = 0; j < mesh.nv; ++j)
    for (Index i = 0; i + 1 < mesh.nu; ++i)
      if (mesh.warp_edge_cells(i, j) > 0) add(mesh.index(i, j), mesh.index(i + 1, j));
  for (Index j = 0; j + 1 < mesh.nv; ++j)
    for (Index i = 0; i < mesh.nu; ++i)
      if (mesh.weft_edge_cells(i, j) > 0) add(mesh.index(i, j), mesh.index(i, j + 1));
  if (which == ConstrainedEdges::triangle_edges)
    for (const auto& q : mesh.quads) add(q[0], q[2]);  // the diagonal ClothMesh::triangles() uses
  return out;
}

double max_edge_strain(const std::vector<EdgeConstraint>& constraints, const Matrix3X& x) {
  double worst = 0.0;
  for (const EdgeConstraint& c : constraints)
    worst = std::max(worst, std::abs(edge_strain(x.row(c.a), x.row(c.b), c.rest_m)));
  return worst;
}

double max_edge_strain(const std::vector<EdgeConstraint>& constraints, const Matrix3X& x,
                       const Eigen::VectorXd& inv_mass) {
  double worst = 0.0;
  for (const EdgeConstraint& c : constraints)
    if (inv_mass[c.a] != 0.0 || inv_mass[c.b] != 0.0)
      worst = std::max(worst, std::abs(edge_strain(x.row(c.a), x.row(c.b), c.rest_m)));
  return worst;
}

void require_held_kept(const Eigen::VectorXd& made, const Eigen::VectorXd& now) {
  if (now.size() != made.size())
    throw std::invalid_argument("projection: inverse masses for " + std::to_string(now.size()) +
                                " vertices, the projector was made for " +
                                std::to_string(made.size()));
  for (Eigen::Index v = 0; v < made.size(); ++v)
    if (made[v] == 0.0 && now[v] != 0.0)
      throw std::invalid_argument("projection: vertex " + std::to_string(v) +
                                  " was held when the projector was made and must stay held");
}

double mean_edge_strain(const std::vector<EdgeConstraint>& constraints, const Matrix3X& x) {
  if (constraints.empty()) return 0.0;
  double sum = 0.0;
  for (const EdgeConstraint& c : constraints) sum += std::abs(edge_strain(x.row(c.a), x.row(c.b), c.rest_m));
  return sum / static_cast<double>(constraints.size());
}

const Eigen::VectorXd& ConstraintProjector::multipliers() const {
  static const Eigen::VectorXd none;
  return none;
}

std::unique_ptr<ConstraintProjector> make_projector(const ClothMesh& mesh,
                                                    const Eigen::VectorXd& inv_mass,
                                                    const ProjectionSettings& settings,
                                                    SparseBackend backend) {
  if (settings.method != ProjectionMethod::none && settings.edges == ConstrainedEdges::warp_weft)
    mesh.require_grid("projection onto inextensible warp/weft edges (simulation.constraints.edges "
                      "warp_weft)");
  switch (settings.method) {
    case ProjectionMethod::none:
      return nullptr;
    case ProjectionMethod::fast_projection:
      return std::make_unique<FastProjection>(make_edge_constraints(mesh, settings.edges, inv_mass),
                                              inv_mass, settings, backend);
    case ProjectionMethod::pairwise:
      return std::make_unique<PairwiseProjection>(
          make_edge_constraints(mesh, settings.edges, inv_mass), inv_mass, settings);
  }
  return nullptr;
}

}  // namespace weft::sim
