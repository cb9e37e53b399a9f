// Area-weighted vertex normals for a RenderMesh, and its validation.

#include "render/render_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_set>

namespace weft::render {

void compute_vertex_normals(RenderMesh& mesh) {
  const std::size_t vertex_count = mesh.positions.size();
  // Accumulate in double: the sum of many small cross products stays accurate.
  std::vector<Eigen::Vector3d> sums(vertex_count, Eigen::Vector3d::Zero());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (std::uint32_t v : t) {
      if (v >= vertex_count) {
        throw std::invalid_argument("compute_vertex_normals: triangle " + std::to_string(f) +
                                    " uses vertex " + std::to_string(v) + " but the mesh has " +
                                    std::to_string(vertex_count) + " vertices");
      }
    }
    const Eigen::Vector3d a = mesh.positions[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions[t[2]].cast<double>();
    // |(b−a)×(c−a)| = 2 × area and points to the side from which a, b, c turn counter-clockwise:
    // adding it unnormalised weights each face by its area; zero-area faces add nothing.
    const Eigen::Vector3d weighted = (b - a).cross(c - a);
    for (std::uint32_t v : t) sums[v] += weighted;
  }

  mesh.normals.resize(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const double length = sums[v].norm();
    // Isolated vertices (and those whose faces cancel exactly) get +z.
    mesh.normals[v] = (length > 0.0 && std::isfinite(length))
                          ? Eigen::Vector3f((sums[v] / length).cast<float>())
                          : Eigen::Vector3f::UnitZ();
  }
}

void validate(const RenderMesh& mesh, const std::string& name) {
  const std::size_t vertex_count = mesh.positions.size();
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (!mesh.positions[v].allFinite()) {
      throw std::invalid_argument(name + ": vertex " + std::to_string(v) +
                                  " has a non-finite position");
    }
  }
  // Every index of every triangle or edge ("triangle", "edge") within the vertices.
  const auto check_indices = [&](const auto& items, const char* what) {
    for (std::size_t k = 0; k < items.size(); ++k) {
      for (std::uint32_t v : items[k]) {
        if (v >= vertex_count) {
          throw std::invalid_argument(name + ": " + what + " " + std::to_string(k) +
                                      " uses vertex " + std::to_string(v) + " but the mesh has " +
                                      std::to_string(vertex_count) + " vertices");
        }
      }
    }
  };
  check_indices(mesh.triangles, "triangle");
  check_indices(mesh.edges, "edge");
}

std::vector<std::array<std::uint32_t, 2>> triangle_edges(const RenderMesh& mesh) {
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::unordered_set<std::uint64_t> seen;
  seen.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      if (seen.insert((std::uint64_t{a} << 32) | b).second) edges.push_back({a, b});
    }
  }
  return edges;
}

const RenderMesh& with_normals(const RenderMesh& mesh, RenderMesh& storage) {
  if (mesh.normals.size() == mesh.positions.size()) return mesh;
  storage.positions = mesh.positions;
  storage.triangles = mesh.triangles;
  storage.uvs = mesh.uvs;
  storage.strain = mesh.strain;
  storage.edges = mesh.edges;
  compute_vertex_normals(storage);
  return storage;
}

}  // namespace weft::render
