#include "sim/remesh/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace weft::sim::remesh {

void check_mesh(const Matrix2X& material, const Triangles& triangles, const char* what) {
  const Index nv = static_cast<Index>(material.rows());
  if (triangles.rows() == 0) throw std::invalid_argument(std::string(what) + ": no triangles");
  for (Index v = 0; v < nv; ++v)
    if (!std::isfinite(material(v, 0)) || !std::isfinite(material(v, 1)))
      throw std::invalid_argument(std::string(what) + ": vertex " + std::to_string(v) +
                                  " has a non-finite material coordinate");
  for (Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k)
      if (triangles(t, k) < 0 || triangles(t, k) >= nv)
        throw std::invalid_argument(std::string(what) + ": triangle " + std::to_string(t) +
                                    " names vertex " + std::to_string(triangles(t, k)) +
                                    ", expected an index in [0, " + std::to_string(nv) + ")");
    const Vec2 a = material.row(triangles(t, 0)), b = material.row(triangles(t, 1)),
               c = material.row(triangles(t, 2));
    if (signed_area2(a, b, c) == 0.0)
      throw std::invalid_argument(std::string(what) + ": triangle " + std::to_string(t) +
                                  " has zero material area (repeated or collinear vertices)");
  }
}

std::vector<std::vector<Index>> vertex_neighbours(Index vertex_count, const Triangles& triangles) {
  std::vector<std::vector<Index>> rings(static_cast<size_t>(vertex_count));
  for (Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = triangles(t, k), b = triangles(t, (k + 1) % 3);
      rings[static_cast<size_t>(a)].push_back(b);
      rings[static_cast<size_t>(b)].push_back(a);
    }
  for (auto& ring : rings) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  return rings;
}

std::vector<std::array<Index, 2>> boundary_edges(const Triangles& triangles) {
  // Undirected edge (min, max) → its uses, each the directed edge as the triangle lists it.
  std::map<std::array<Index, 2>, std::vector<std::array<Index, 2>>> uses;
  for (Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = triangles(t, k), b = triangles(t, (k + 1) % 3);
      uses[{std::min(a, b), std::max(a, b)}].push_back({a, b});
    }
  std::vector<std::array<Index, 2>> boundary;
  for (const auto& [edge, directed] : uses) {
    if (directed.size() > 2)
      throw std::invalid_argument("mesh: edge (" + std::to_string(edge[0]) + ", " +
                                  std::to_string(edge[1]) + ") is shared by " +
                                  std::to_string(directed.size()) +
                                  " triangles, expected at most 2 (a non-manifold mesh)");
    if (directed.size() == 1) boundary.push_back(directed.front());
  }
  return boundary;
}

int orientation(const Matrix2X& material, const Triangles& triangles) {
  int sign = 0;
  for (Index t = 0; t < triangles.rows(); ++t) {
    const double a2 = signed_area2(material.row(triangles(t, 0)), material.row(triangles(t, 1)),
                                   material.row(triangles(t, 2)));
    const int s = a2 > 0.0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign)
      throw std::invalid_argument("mesh: triangle " + std::to_string(t) +
                                  " is oriented against triangle 0 in material coordinates");
  }
  return sign;
}

}  // namespace weft::sim::remesh
