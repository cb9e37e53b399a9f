#include "app/run/frame_mesh.h"

#include <limits>
#include <vector>

#include "sim/constraints/inextensibility.h"
#include "sim/constraints/projection.h"

namespace weft::app {

std::vector<double> vertex_strains(const sim::ClothMesh& mesh, const sim::Matrix3X& x) {
  const auto n = static_cast<std::size_t>(x.rows());
  const Eigen::VectorXd free = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(n));
  std::vector<double> sum(n, 0.0);
  std::vector<int> count(n, 0);
  for (const sim::EdgeConstraint& e :
       sim::make_edge_constraints(mesh, sim::ConstrainedEdges::warp_weft, free)) {
    const double strain = sim::edge_strain(x.row(e.a), x.row(e.b), e.rest_m);
    for (const sim::Index v : {e.a, e.b}) {
      sum[static_cast<std::size_t>(v)] += strain;
      ++count[static_cast<std::size_t>(v)];
    }
  }
  for (std::size_t v = 0; v < n; ++v)
    if (count[v] > 0) sum[v] /= count[v];
  return sum;
}

render::RenderMesh to_render_mesh(const sim::ClothMesh& mesh, const sim::Matrix3X& x) {
  render::RenderMesh out;
  const auto n = static_cast<std::size_t>(x.rows());
  // Only the used vertices, in their order: the unused ones of a trimmed specimen (outside a
  // disc) are left out altogether, so that nothing — the shadow pass's bounds included — sees
  // them. A rectangle uses every vertex and keeps the simulator's numbering.
  constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> slot(n, unused);
  out.positions.reserve(n);
  out.uvs.reserve(n);
  out.strain.reserve(n);
  const std::vector<double> strain = vertex_strains(mesh, x);
  for (std::size_t k = 0; k < n; ++k) {
    if (!mesh.vertex_used[k]) continue;
    slot[k] = static_cast<std::uint32_t>(out.positions.size());
    out.positions.push_back(x.row(static_cast<Eigen::Index>(k)).transpose().cast<float>());
    out.uvs.push_back(mesh.material_coords[k].cast<float>());
    out.strain.push_back(static_cast<float>(strain[k]));
  }
  for (const auto& t : mesh.triangles())
    out.triangles.push_back({slot[static_cast<std::size_t>(t[0])], slot[static_cast<std::size_t>(t[1])],
                             slot[static_cast<std::size_t>(t[2])]});
  // The wireframe's lines: a grid's warp and weft edges (not the cells' diagonals); a mesh
  // without a grid leaves them empty, so that every triangle side is drawn.
  if (mesh.has_grid()) {
    const auto line = [&](sim::Index a, sim::Index b) {
      out.edges.push_back({slot[static_cast<std::size_t>(a)], slot[static_cast<std::size_t>(b)]});
    };
    for (sim::Index j = 0; j < mesh.nv; ++j) {
      for (sim::Index i = 0; i < mesh.nu; ++i) {
        if (mesh.warp_edge_cells(i, j) > 0) line(mesh.index(i, j), mesh.index(i + 1, j));
        if (mesh.weft_edge_cells(i, j) > 0) line(mesh.index(i, j), mesh.index(i, j + 1));
      }
    }
  }
  render::compute_vertex_normals(out);
  return out;
}

}  // namespace weft::app
