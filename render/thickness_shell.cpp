// The closed offset shell of a cloth sheet (thickness_shell.h). Boundary edges are those in
// exactly one triangle; each keeps the direction a → b its triangle walks it in, so that the
// rim quad (upper a, upper b, lower b, lower a) can be split into two triangles facing
// (b − a) × n, away from the sheet.

#include "render/thickness_shell.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace weft::render {

RenderMesh make_thickness_shell(const RenderMesh& input, double thickness_m) {
  if (!(thickness_m > 0.0) || !std::isfinite(thickness_m)) {
    throw std::invalid_argument("make_thickness_shell: thickness must be finite and > 0, got " +
                                std::to_string(thickness_m));
  }
  validate(input, "make_thickness_shell");
  if (!input.uvs.empty() && input.uvs.size() != input.positions.size()) {
    throw std::invalid_argument("make_thickness_shell: the mesh has " +
                                std::to_string(input.uvs.size()) + " UVs for " +
                                std::to_string(input.positions.size()) + " vertices");
  }
  const std::size_t n = input.positions.size();
  if (2 * n > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("make_thickness_shell: the shell does not fit 32-bit indices");
  RenderMesh normals_storage;
  const RenderMesh& mesh = with_normals(input, normals_storage);
  const auto lower = static_cast<std::uint32_t>(n);  // index offset of the lower sheet

  RenderMesh shell;
  shell.positions.resize(2 * n);
  const float half = static_cast<float>(0.5 * thickness_m);
  for (std::size_t v = 0; v < n; ++v) {
    shell.positions[v] = mesh.positions[v] + half * mesh.normals[v];
    shell.positions[n + v] = mesh.positions[v] - half * mesh.normals[v];
  }
  if (!mesh.uvs.empty()) {
    shell.uvs = mesh.uvs;
    shell.uvs.insert(shell.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
  }
  if (mesh.strain.size() == n) {
    shell.strain = mesh.strain;
    shell.strain.insert(shell.strain.end(), mesh.strain.begin(), mesh.strain.end());
  }

  // Directed edges by their undirected key: how many triangles hold each, and the direction
  // of the first (the one a boundary edge has).
  std::map<std::pair<std::uint32_t, std::uint32_t>,
           std::pair<int, std::pair<std::uint32_t, std::uint32_t>>>
      edges;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order;  // keys as first met
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      const auto key = std::minmax(a, b);
      auto [it, inserted] = edges.try_emplace(key, 0, std::pair{a, b});
      if (inserted) order.push_back(key);
      ++it->second.first;
    }
  }

  shell.triangles.reserve(2 * mesh.triangles.size() + 2 * order.size());
  for (const auto& t : mesh.triangles) shell.triangles.push_back(t);
  for (const auto& t : mesh.triangles)
    shell.triangles.push_back({t[0] + lower, t[1] + lower, t[2] + lower});
  for (const auto& key : order) {
    const auto& [count, direction] = edges.at(key);
    if (count != 1) continue;
    const auto [a, b] = direction;
    // (upper a, lower a, upper b) and (upper b, lower a, lower b): both face (b − a) × n.
    shell.triangles.push_back({a, a + lower, b});
    shell.triangles.push_back({b, a + lower, b + lower});
  }
  // The wireframe on both sheets.
  shell.edges.reserve(2 * mesh.edges.size());
  for (const auto& e : mesh.edges) shell.edges.push_back(e);
  for (const auto& e : mesh.edges) shell.edges.push_back({e[0] + lower, e[1] + lower});
  compute_vertex_normals(shell);
  return shell;
}

}  // namespace weft::render
