// A triangle-mesh cloth saved and read back bit for bit (see cloth_mesh_archive.h).

#include "sim/cloth_mesh_archive.h"

#include <string>

#include "base/check.h"

namespace weft::sim {
namespace {

// #V×2 (u, v): the material coordinates as one matrix (Vec2 is not trivially copyable).
using MaterialRows = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

}  // namespace

void save_cloth_mesh(StateWriter& out, const ClothMesh& mesh) {
  WEFT_CHECK(!mesh.has_grid(),
             "save_cloth_mesh: " + mesh.name() + " is a warp/weft grid, made anew from the scene");
  out.section("cloth mesh");
  MaterialRows material(static_cast<Eigen::Index>(mesh.material_coords.size()), 2);
  for (std::size_t k = 0; k < mesh.material_coords.size(); ++k)
    material.row(static_cast<Eigen::Index>(k)) = mesh.material_coords[k].transpose();
  out.matrix(material);
  out.pods(mesh.faces);
  out.matrix(mesh.rest_positions);
  out.matrix(mesh.start_positions);
  out.matrix(mesh.vertex_area_m2);
  std::vector<char> used(mesh.vertex_used.begin(), mesh.vertex_used.end());
  out.pods(used);
  out.section("cloth mesh end");
}

void restore_cloth_mesh(StateReader& in, ClothMesh& mesh) {
  in.section("cloth mesh");
  ClothMesh read;
  read.source = mesh.source;
  MaterialRows material;
  in.matrix(material, -1, 2);
  const auto n = static_cast<Index>(material.rows());
  read.material_coords.resize(static_cast<std::size_t>(n));
  for (Index k = 0; k < n; ++k)
    read.material_coords[static_cast<std::size_t>(k)] = material.row(k).transpose();
  in.pods(read.faces);
  in.matrix(read.rest_positions, n, 3);
  in.matrix(read.start_positions, -1, 3);  // no rows (the rest shape) or #V
  if (read.start_positions.rows() != 0 && read.start_positions.rows() != n)
    in.fail("start positions of " + std::to_string(read.start_positions.rows()) +
            " vertices for a mesh of " + std::to_string(n));
  in.matrix(read.vertex_area_m2, n, 1);
  std::vector<char> used;
  in.pods(used);
  if (static_cast<Index>(used.size()) != n)
    in.fail(std::to_string(used.size()) + " used-vertex flags for " + std::to_string(n) +
            " vertices");
  read.vertex_used.assign(used.begin(), used.end());
  for (std::size_t f = 0; f < read.faces.size(); ++f)
    for (const Index v : read.faces[f])
      if (v < 0 || v >= n)
        in.fail("triangle " + std::to_string(f) + " has the corner " + std::to_string(v) +
                ", not one of the " + std::to_string(n) + " vertices");
  in.section("cloth mesh end");
  mesh = std::move(read);
}

}  // namespace weft::sim
