#include "app/frame_mesh.h"

namespace weft::app {

render::RenderMesh to_render_mesh(const sim::ClothMesh& mesh, const sim::Matrix3X& x) {
  render::RenderMesh out;
  const auto n = static_cast<std::size_t>(x.rows());
  out.positions.resize(n);
  out.uvs.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    out.positions[k] = x.row(static_cast<Eigen::Index>(k)).transpose().cast<float>();
    out.uvs[k] = mesh.material_coords[k].cast<float>();
  }
  for (const auto& t : mesh.triangles())
    out.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                             static_cast<std::uint32_t>(t[2])});
  render::compute_vertex_normals(out);
  return out;
}

}  // namespace weft::app
