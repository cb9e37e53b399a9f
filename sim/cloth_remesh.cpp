// Remeshing a simulated cloth (see cloth_remesh.h); needs CGAL (sim/remesh).

#include "sim/cloth_remesh.h"

#include <stdexcept>

#include "sim/remesh/curvature.h"
#include "sim/remesh/remesh.h"
#include "sim/remesh/size_field.h"
#include "sim/triangle_cloth.h"

namespace weft::sim {

void check_remesh_settings(const ClothMesh& mesh, const SimSettings& settings) {
  if (!settings.remesh.enabled) return;
  const std::string key = "simulation.remesh: ";
  if (mesh.has_grid())
    throw std::invalid_argument(
        key + "needs a triangle-mesh cloth (cloth.mesh, a file of triangles); " + mesh.name() +
        " is a warp/weft grid, whose models run on its quads and edges, which a remesh replaces "
        "by triangles (docs/remeshing.md)");
  if (settings.model == ClothModel::mass_spring)
    throw std::invalid_argument(
        key + "not with simulation.model \"mass_spring\": on a triangle mesh its springs' "
              "stiffness comes from the triangles' edge directions, so each remesh would change "
              "the cloth's rigidity; use baraff_witkin");
  if (settings.model == ClothModel::rft3 || settings.model == ClothModel::rft6)
    throw std::invalid_argument(
        key + "not with simulation.model \"" + cloth_model_name(settings.model) +
        "\": RFT bending needs a non-degenerate six-node patch around every triangle, which a "
        "Delaunay remesh does not guarantee (a remeshed drape stopped on a degenerate patch); "
        "use baraff_witkin");
  if (is_explicit(settings.integrator))
    throw std::invalid_argument(
        key + "needs simulation.integrator implicit_euler or dynamic_relaxation: an explicit "
              "integrator's step is set once from the first mesh's critical step, which a finer "
              "mesh lowers");
  if (settings.projection.method != ProjectionMethod::none)
    throw std::invalid_argument(
        key + "not with simulation.constraints: fast projection needs warp/weft edges, which a "
              "remeshed cloth has none of, and triangle-edge constraints lock");
  if (settings.time_step.is_adaptive())
    throw std::invalid_argument(key + "not with time_step \"adaptive\" (it follows fast "
                                      "projection, which a remeshed cloth cannot use)");
}

namespace {

remesh::Triangles remesh_triangle_rows(const ClothMesh& mesh) {
  remesh::Triangles t(static_cast<Eigen::Index>(mesh.faces.size()), 3);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int c = 0; c < 3; ++c)
      t(static_cast<Eigen::Index>(f), c) = mesh.faces[f][static_cast<std::size_t>(c)];
  return t;
}

remesh::Matrix2X remesh_material_rows(const ClothMesh& mesh) {
  remesh::Matrix2X m(mesh.vertex_count(), 2);
  for (Index k = 0; k < mesh.vertex_count(); ++k)
    m.row(k) = mesh.material_coords[static_cast<std::size_t>(k)].transpose();
  return m;
}

remesh::SizeFieldParams remesh_size_params(const RemeshSettings& settings) {
  remesh::SizeFieldParams size;
  size.c_m = settings.c_m;
  size.h_min_m = settings.h_min_m;
  size.h_max_m = settings.h_max_m;
  return size;
}

}  // namespace

double cloth_remesh_indicator_m(const ClothMesh& mesh, const Matrix3X& x,
                                const RemeshSettings& settings) {
  return cloth_remesh_criteria(mesh, x, settings).indicator_m;
}

ClothRemeshCriteria cloth_remesh_criteria(const ClothMesh& mesh, const Matrix3X& x,
                                          const RemeshSettings& settings) {
  const remesh::Matrix2X material = remesh_material_rows(mesh);
  const remesh::Triangles triangles = remesh_triangle_rows(mesh);
  const Eigen::VectorXd curvature = remesh::vertex_curvature(material, triangles, x);
  const remesh::SizeFieldParams size = remesh_size_params(settings);
  return {remesh::remesh_indicator(material, triangles, curvature, size),
          remesh::refinement_excess(material, triangles, curvature, size)};
}

RemeshedCloth remesh_cloth(const ClothMesh& mesh, const Matrix3X& x, const Matrix3X& v,
                           const Matrix3X& initial_x, const std::vector<Index>& keep,
                           const RemeshSettings& settings) {
  if (mesh.has_grid())
    throw std::invalid_argument("remesh_cloth: " + mesh.name() + " is a warp/weft grid, not a "
                                "triangle mesh");
  remesh::RemeshInput in;
  const Index n_old = mesh.vertex_count();
  in.material = remesh_material_rows(mesh);
  in.triangles = remesh_triangle_rows(mesh);
  in.positions = x;
  in.velocities = v;
  in.pins = keep;
  remesh::RemeshParams params;
  params.size = remesh_size_params(settings);
  params.positions = settings.transfer;
  params.mesher.max_vertices = static_cast<Index>(settings.max_vertices);
  const remesh::RemeshOutput out = remesh::remesh(in, params);

  ClothPattern pattern;
  const Index n_new = static_cast<Index>(out.mesh.material.rows());
  pattern.material_coords.resize(static_cast<std::size_t>(n_new));
  for (Index k = 0; k < n_new; ++k)
    pattern.material_coords[static_cast<std::size_t>(k)] = out.mesh.material.row(k).transpose();
  pattern.start_positions = remesh::transfer(out.transfer, in.triangles, mesh.start());
  pattern.faces.reserve(static_cast<std::size_t>(out.mesh.triangles.rows()));
  for (Eigen::Index f = 0; f < out.mesh.triangles.rows(); ++f)
    pattern.faces.push_back(
        {out.mesh.triangles(f, 0), out.mesh.triangles(f, 1), out.mesh.triangles(f, 2)});
  pattern.source = mesh.source;

  RemeshedCloth cloth;
  cloth.mesh = make_pattern_cloth(pattern);
  // The rest shape is the pattern laid in space, affine in (u, v): interpolation keeps it
  // (the kept vertices exactly).
  cloth.mesh.rest_positions = remesh::transfer(out.transfer, in.triangles, mesh.rest_positions);
  cloth.x = out.positions;
  cloth.v = out.velocities;
  cloth.initial_x = remesh::transfer(out.transfer, in.triangles, initial_x);
  cloth.old_to_new.assign(static_cast<std::size_t>(n_old), -1);
  for (Index k = 0; k < n_new; ++k)
    if (const Index old = out.mesh.new_to_old[static_cast<std::size_t>(k)]; old >= 0)
      cloth.old_to_new[static_cast<std::size_t>(old)] = k;
  return cloth;
}

}  // namespace weft::sim
