// The cloth from a mesh file (see cloth_mesh_file.h).

#include "app/io/cloth_mesh_file.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "app/io/mesh_file.h"
#include "sim/triangle_cloth.h"

namespace weft::app {
namespace {

// The flat mesh's own 2-D coordinates, in file units (cloth_mesh_file.h).
std::vector<sim::Vec2> plane_coordinates(const PolygonMesh& mesh, const std::string& name) {
  const auto p = [&](sim::Index v) -> sim::Vec3 { return mesh.vertices.row(v).transpose(); };
  sim::Vec3 normal = sim::Vec3::Zero();
  for (const auto& f : mesh.faces)
    for (std::size_t c = 0; c < f.size(); ++c) normal += p(f[c]).cross(p(f[(c + 1) % f.size()]));
  if (!(normal.norm() > 0.0))
    throw MeshFileError(name + ": the mesh has no area, so no plane to flatten it in");
  normal.normalize();
  const sim::Vec3 lo = mesh.vertices.colwise().minCoeff().transpose();
  const sim::Vec3 hi = mesh.vertices.colwise().maxCoeff().transpose();
  const double size = (hi - lo).norm();
  const sim::Vec3 origin = p(0);
  for (sim::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const double off = std::abs((p(v) - origin).dot(normal));
    if (off > 1e-6 * size)
      throw MeshFileError(name + ": the mesh is not flat (vertex " + std::to_string(v) + " is " +
                          std::to_string(off) + " file units off its plane), so its own " +
                          "coordinates cannot be its pattern: give it texture coordinates (UVs) "
                          "and cloth.pattern \"uv\"");
  }
  sim::Vec3 first = sim::Vec3::UnitX() - normal.x() * normal;
  if (first.norm() < 0.5) first = sim::Vec3::UnitY() - normal.y() * normal;
  first.normalize();
  const sim::Vec3 second = normal.cross(first);
  std::vector<sim::Vec2> out(static_cast<std::size_t>(mesh.vertices.rows()));
  sim::Vec2 least = sim::Vec2::Constant(INFINITY);
  for (sim::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const sim::Vec3 d = p(v) - origin;
    out[static_cast<std::size_t>(v)] = {d.dot(first), d.dot(second)};
    least = least.cwiseMin(out[static_cast<std::size_t>(v)]);
  }
  for (sim::Vec2& x : out) x -= least;
  return out;
}

// Each cloth vertex's colour: a triangle mesh keeps the file's numbering; a grid is renumbered
// (sim/triangle_cloth.h), and its vertex takes its start position bit for bit from the file's
// vertex, which finds it. Lattice points of no quad (unused) are NaN: they match no colour.
// Empty: no colours.
std::vector<Eigen::Vector3d> cloth_vertex_colours(const PolygonMesh& file,
                                                  const sim::ClothPattern& pattern,
                                                  const sim::ClothMesh& cloth) {
  if (file.colour.empty()) return {};
  if (!cloth.has_grid()) return file.colour;
  std::map<std::array<double, 3>, sim::Index> file_vertex_at;
  for (sim::Index v = 0; v < pattern.start_positions.rows(); ++v)
    file_vertex_at.emplace(std::array<double, 3>{pattern.start_positions(v, 0),
                                                 pattern.start_positions(v, 1),
                                                 pattern.start_positions(v, 2)},
                           v);
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(cloth.vertex_count()),
                                   Eigen::Vector3d::Constant(NAN));
  for (sim::Index v = 0; v < cloth.vertex_count(); ++v) {
    if (!cloth.is_used(v)) continue;
    const auto it = file_vertex_at.find(
        {cloth.start()(v, 0), cloth.start()(v, 1), cloth.start()(v, 2)});
    if (it != file_vertex_at.end())
      out[static_cast<std::size_t>(v)] = file.colour[static_cast<std::size_t>(it->second)];
  }
  return out;
}

}  // namespace

sim::ClothMesh load_cloth_mesh(const ClothMeshFileSpec& spec, std::vector<Eigen::Vector3d>* colour) {
  const std::string name = spec.path.string();
  const PolygonMesh mesh = load_polygon_mesh(spec.path);  // throws MeshFileError
  PatternSource source = spec.pattern;
  if (source == PatternSource::automatic)
    source = mesh.uv.empty() ? PatternSource::plane : PatternSource::uv;

  std::vector<sim::Vec2> pattern;
  if (source == PatternSource::uv) {
    if (mesh.uv.empty())
      throw MeshFileError(name + ": no texture coordinates (UVs) in the mesh file (on every "
                          "mesh of it), which cloth.pattern \"uv\" needs for the flat pattern; "
                          "a flat mesh can use \"plane\"");
    if (mesh.uv_seam_vertex >= 0)
      throw MeshFileError(name + ": vertex " + std::to_string(mesh.uv_seam_vertex) +
                          " has two different texture coordinates (a UV seam); a cloth mesh "
                          "needs one pattern point per vertex: cut the mesh along the seam");
    for (const sim::Vec2& t : mesh.uv) pattern.push_back(spec.uv_scale_m * t);
  } else {
    for (const sim::Vec2& x : plane_coordinates(mesh, name)) pattern.push_back(spec.scale * x);
  }
  if (spec.warp_angle_rad != 0.0) {
    const double c = std::cos(spec.warp_angle_rad), s = std::sin(spec.warp_angle_rad);
    for (sim::Vec2& x : pattern) x = sim::Vec2(c * x.x() + s * x.y(), -s * x.x() + c * x.y());
  }

  sim::ClothPattern cloth;
  cloth.material_coords = std::move(pattern);
  cloth.origin = spec.origin;
  cloth.warp_axis = spec.warp_axis;
  cloth.weft_axis = spec.weft_axis;
  cloth.source = spec.path.filename().string();
  const sim::Vec3 normal = spec.warp_axis.cross(spec.weft_axis);
  cloth.start_positions.resize(mesh.vertices.rows(), 3);
  for (sim::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const sim::Vec3 x = mesh.vertices.row(v).transpose();
    cloth.start_positions.row(v) =
        (spec.origin + spec.scale * (x.x() * spec.warp_axis + x.y() * spec.weft_axis + x.z() * normal))
            .transpose();
  }
  cloth.faces.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) cloth.faces.push_back(f);
  sim::ClothMesh out;
  try {
    out = sim::make_pattern_cloth(cloth);
  } catch (const std::invalid_argument& e) {
    throw MeshFileError(name + ": " + e.what());
  }
  if (colour) *colour = cloth_vertex_colours(mesh, cloth, out);
  return out;
}

}  // namespace weft::app
