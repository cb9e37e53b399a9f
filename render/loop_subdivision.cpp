// Loop subdivision (see loop_subdivision.h for the masks). One level:
//   1. edges: a table of the mesh's edges (keyed by their sorted end indices), the triangles
//      on each and their opposite vertices,
//   2. per vertex: valence, the sum of its neighbours, and its boundary edges' other ends,
//   3. new positions: old vertices moved by the vertex masks, one edge point per edge,
//   4. each triangle (a, b, c) with edge points ab, bc, ca becomes
//      (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca): orientation kept.
// Sums are taken in double, so the result does not depend on float rounding of partial sums
// more than once per level.

#include "render/loop_subdivision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace weft::render {

namespace {

constexpr double pi = 3.14159265358979323846;

struct Edge {
  std::uint32_t a = 0, b = 0;          // ends, a < b
  int faces = 0;                       // triangles on the edge
  std::uint32_t opposite[2] = {0, 0};  // the third vertex of the first two of them
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

// Loop's weight of each neighbour of an interior vertex of valence n.
double loop_beta(int n) {
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * pi / n);
  return (5.0 / 8.0 - c * c) / n;
}

RenderMesh subdivide_once(const RenderMesh& mesh) {
  const std::size_t vertex_count = mesh.positions.size();
  const bool has_uvs = !mesh.uvs.empty();

  // 1. Edges, in the order first met; per triangle the indices of its edges ab, bc, ca.
  std::vector<Edge> edges;
  std::unordered_map<std::uint64_t, std::uint32_t> edge_index;
  edge_index.reserve(3 * mesh.triangles.size());
  std::vector<std::array<std::uint32_t, 3>> triangle_edges(mesh.triangles.size());
  std::vector<int> face_count(vertex_count, 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      ++face_count[t[k]];
      const std::uint32_t a = t[k], b = t[(k + 1) % 3], opposite = t[(k + 2) % 3];
      const auto [it, inserted] =
          edge_index.emplace(edge_key(a, b), static_cast<std::uint32_t>(edges.size()));
      if (inserted) edges.push_back({std::min(a, b), std::max(a, b), 0, {0, 0}});
      Edge& e = edges[it->second];
      if (e.faces < 2) e.opposite[e.faces] = opposite;
      ++e.faces;
      triangle_edges[f][k] = it->second;
    }
  }
  const std::size_t new_count = vertex_count + edges.size();
  if (new_count > std::numeric_limits<std::uint32_t>::max() ||
      4 * mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("loop_subdivide: the subdivided mesh does not fit 32-bit indices");
  }

  // 2. Per vertex: neighbours over all edges, and over boundary edges (one triangle).
  std::vector<Eigen::Vector3d> neighbour_sum(vertex_count, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> boundary_sum(vertex_count, Eigen::Vector3d::Zero());
  std::vector<int> valence(vertex_count, 0), boundary_edges(vertex_count, 0);
  std::vector<bool> non_manifold(vertex_count, false);
  for (const Edge& e : edges) {
    const Eigen::Vector3d pa = mesh.positions[e.a].cast<double>();
    const Eigen::Vector3d pb = mesh.positions[e.b].cast<double>();
    neighbour_sum[e.a] += pb;
    neighbour_sum[e.b] += pa;
    ++valence[e.a];
    ++valence[e.b];
    if (e.faces == 1) {
      boundary_sum[e.a] += pb;
      boundary_sum[e.b] += pa;
      ++boundary_edges[e.a];
      ++boundary_edges[e.b];
    } else if (e.faces > 2) {
      non_manifold[e.a] = non_manifold[e.b] = true;
    }
  }

  // 3. Positions and UVs.
  RenderMesh out;
  out.positions.resize(new_count);
  if (has_uvs) out.uvs.resize(new_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const Eigen::Vector3d p = mesh.positions[v].cast<double>();
    Eigen::Vector3d moved = p;
    if (non_manifold[v] || valence[v] == 0) {
      // kept
    } else if (boundary_edges[v] == 0) {
      const double beta = loop_beta(valence[v]);
      moved = (1.0 - valence[v] * beta) * p + beta * neighbour_sum[v];
    } else if (boundary_edges[v] == 2 && face_count[v] >= 3) {
      moved = 0.75 * p + 0.125 * boundary_sum[v];
    }  // else a corner: kept
    out.positions[v] = moved.cast<float>();
    if (has_uvs) out.uvs[v] = mesh.uvs[v];
  }
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    const Eigen::Vector3d pa = mesh.positions[e.a].cast<double>();
    const Eigen::Vector3d pb = mesh.positions[e.b].cast<double>();
    Eigen::Vector3d point = 0.5 * (pa + pb);
    if (e.faces == 2) {
      point = 0.375 * (pa + pb) + 0.125 * (mesh.positions[e.opposite[0]].cast<double>() +
                                           mesh.positions[e.opposite[1]].cast<double>());
    }
    out.positions[vertex_count + k] = point.cast<float>();
    if (has_uvs) out.uvs[vertex_count + k] = 0.5f * (mesh.uvs[e.a] + mesh.uvs[e.b]);
  }

  // 4. Four triangles per triangle.
  out.triangles.reserve(4 * mesh.triangles.size());
  const auto base = static_cast<std::uint32_t>(vertex_count);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const std::uint32_t ab = base + triangle_edges[f][0], bc = base + triangle_edges[f][1],
                        ca = base + triangle_edges[f][2];
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

}  // namespace

RenderMesh loop_subdivide(const RenderMesh& mesh, int levels) {
  if (levels < 0 || levels > max_subdivision_levels) {
    throw std::invalid_argument("loop_subdivide: levels must be in 0.." +
                                std::to_string(max_subdivision_levels) + ", got " +
                                std::to_string(levels));
  }
  validate(mesh, "loop_subdivide");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
    throw std::invalid_argument("loop_subdivide: the mesh has " + std::to_string(mesh.uvs.size()) +
                                " UVs for " + std::to_string(mesh.positions.size()) + " vertices");
  }
  RenderMesh out = mesh;
  for (int level = 0; level < levels; ++level) out = subdivide_once(out);
  if (levels > 0 || out.normals.size() != out.positions.size()) compute_vertex_normals(out);
  return out;
}

}  // namespace weft::render
