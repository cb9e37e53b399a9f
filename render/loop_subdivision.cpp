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

#include "base/constants.h"

namespace weft::render {

namespace {

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
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * base::kPi / n);
  return (5.0 / 8.0 - c * c) / n;
}

// Step 1: edges in the order first met; per triangle the indices of its edges ab, bc, ca.
struct EdgeTable {
  std::vector<Edge> edges;
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;
  std::vector<int> face_count;  // per vertex: triangles on it
  // edge_key → the edge's index in `edges`
  std::unordered_map<std::uint64_t, std::uint32_t> edge_index;
};

EdgeTable build_edges(const RenderMesh& mesh) {
  EdgeTable table;
  auto& edge_index = table.edge_index;
  edge_index.reserve(3 * mesh.triangles.size());
  table.triangle_edges.resize(mesh.triangles.size());
  table.face_count.assign(mesh.positions.size(), 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      ++table.face_count[t[k]];
      const std::uint32_t a = t[k], b = t[(k + 1) % 3], opposite = t[(k + 2) % 3];
      const auto [it, inserted] =
          edge_index.emplace(edge_key(a, b), static_cast<std::uint32_t>(table.edges.size()));
      if (inserted) table.edges.push_back({std::min(a, b), std::max(a, b), 0, {0, 0}});
      Edge& e = table.edges[it->second];
      if (e.faces < 2) e.opposite[e.faces] = opposite;
      ++e.faces;
      table.triangle_edges[f][k] = it->second;
    }
  }
  return table;
}

// Step 2: per vertex, neighbours over all edges and over boundary edges (one triangle).
struct Neighbours {
  std::vector<Eigen::Vector3d> sum, boundary_sum;
  std::vector<int> valence, boundary_edges;
  std::vector<bool> non_manifold;  // on an edge of more than two triangles
};

Neighbours gather_neighbours(const RenderMesh& mesh, const std::vector<Edge>& edges) {
  const std::size_t vertex_count = mesh.positions.size();
  Neighbours n;
  n.sum.assign(vertex_count, Eigen::Vector3d::Zero());
  n.boundary_sum.assign(vertex_count, Eigen::Vector3d::Zero());
  n.valence.assign(vertex_count, 0);
  n.boundary_edges.assign(vertex_count, 0);
  n.non_manifold.assign(vertex_count, false);
  for (const Edge& e : edges) {
    const Eigen::Vector3d pa = mesh.positions[e.a].cast<double>();
    const Eigen::Vector3d pb = mesh.positions[e.b].cast<double>();
    n.sum[e.a] += pb;
    n.sum[e.b] += pa;
    ++n.valence[e.a];
    ++n.valence[e.b];
    if (e.faces == 1) {
      n.boundary_sum[e.a] += pb;
      n.boundary_sum[e.b] += pa;
      ++n.boundary_edges[e.a];
      ++n.boundary_edges[e.b];
    } else if (e.faces > 2) {
      n.non_manifold[e.a] = n.non_manifold[e.b] = true;
    }
  }
  return n;
}

// Step 3: the old vertices moved by the vertex masks, then one point per edge; UVs carried
// (old vertices) and averaged (edge points) when the mesh has them; strains likewise.
void place_vertices(const RenderMesh& mesh, const EdgeTable& table, const Neighbours& n,
                    RenderMesh& out) {
  const std::size_t vertex_count = mesh.positions.size();
  const bool has_uvs = !mesh.uvs.empty();
  out.positions.resize(vertex_count + table.edges.size());
  if (has_uvs) out.uvs.resize(out.positions.size());
  const bool has_strain = mesh.strain.size() == vertex_count;
  if (has_strain) out.strain.resize(out.positions.size());
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const Eigen::Vector3d p = mesh.positions[v].cast<double>();
    Eigen::Vector3d moved = p;
    if (n.non_manifold[v] || n.valence[v] == 0) {
      // kept
    } else if (n.boundary_edges[v] == 0) {
      const double beta = loop_beta(n.valence[v]);
      moved = (1.0 - n.valence[v] * beta) * p + beta * n.sum[v];
    } else if (n.boundary_edges[v] == 2 && table.face_count[v] >= 3) {
      moved = 0.75 * p + 0.125 * n.boundary_sum[v];
    }  // else a corner: kept
    out.positions[v] = moved.cast<float>();
    if (has_uvs) out.uvs[v] = mesh.uvs[v];
    if (has_strain) out.strain[v] = mesh.strain[v];
  }
  for (std::size_t k = 0; k < table.edges.size(); ++k) {
    const Edge& e = table.edges[k];
    const Eigen::Vector3d pa = mesh.positions[e.a].cast<double>();
    const Eigen::Vector3d pb = mesh.positions[e.b].cast<double>();
    Eigen::Vector3d point = 0.5 * (pa + pb);
    if (e.faces == 2) {
      point = 0.375 * (pa + pb) + 0.125 * (mesh.positions[e.opposite[0]].cast<double>() +
                                           mesh.positions[e.opposite[1]].cast<double>());
    }
    out.positions[vertex_count + k] = point.cast<float>();
    if (has_uvs) out.uvs[vertex_count + k] = 0.5f * (mesh.uvs[e.a] + mesh.uvs[e.b]);
    if (has_strain) out.strain[vertex_count + k] = 0.5f * (mesh.strain[e.a] + mesh.strain[e.b]);
  }
}

RenderMesh subdivide_once(const RenderMesh& mesh) {
  const EdgeTable table = build_edges(mesh);
  const std::size_t new_count = mesh.positions.size() + table.edges.size();
  if (new_count > std::numeric_limits<std::uint32_t>::max() ||
      4 * mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("loop_subdivide: the subdivided mesh does not fit 32-bit indices");
  }
  RenderMesh out;
  place_vertices(mesh, table, gather_neighbours(mesh, table.edges), out);

  // 4. Four triangles per triangle.
  out.triangles.reserve(4 * mesh.triangles.size());
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const auto& e = table.triangle_edges[f];
    const std::uint32_t ab = base + e[0], bc = base + e[1], ca = base + e[2];
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }

  // 5. Each wireframe edge ab becomes its two halves a–m, m–b through its edge point m.
  out.edges.reserve(2 * mesh.edges.size());
  for (std::size_t k = 0; k < mesh.edges.size(); ++k) {
    const auto [a, b] = mesh.edges[k];
    const auto it = table.edge_index.find(edge_key(a, b));
    if (it == table.edge_index.end())
      throw std::invalid_argument("loop_subdivide: edge " + std::to_string(k) + " (" +
                                  std::to_string(a) + ", " + std::to_string(b) +
                                  ") is no triangle's side");
    out.edges.push_back({a, base + it->second});
    out.edges.push_back({base + it->second, b});
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
