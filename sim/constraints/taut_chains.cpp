#include "sim/constraints/taut_chains.h"

#include <algorithm>
#include <cmath>

namespace weft::sim {

TautChains find_taut_chains(const ClothMesh& mesh, const Matrix3X& x,
                            const std::vector<Index>& still_pins,
                            const std::vector<Index>& moving_pins, double relative_tolerance) {
  std::vector<char> pinned(static_cast<std::size_t>(mesh.vertex_count()), 0);  // 1 still, 2 moving
  for (Index p : still_pins) pinned[static_cast<std::size_t>(p)] = 1;
  for (Index p : moving_pins) pinned[static_cast<std::size_t>(p)] = 2;
  TautChains out;
  // One grid line: vertex(k) for k = 0..count−1, edge_exists(k) for the edge from k to k + 1.
  const auto scan = [&](Index count, auto&& vertex, auto&& edge_exists) {
    Index start = -1;  // the last pinned vertex reached along an unbroken chain, or −1
    double rest_length = 0.0;
    bool edges_at_rest = true;
    for (Index k = 0; k < count; ++k) {
      const Index v = vertex(k);
      if (start >= 0 && k > start) {
        const Index a = vertex(k - 1);
        const double rest = (mesh.material_coords[v] - mesh.material_coords[a]).norm();
        rest_length += rest;
        edges_at_rest = edges_at_rest &&
                        std::abs((x.row(v) - x.row(a)).norm() - rest) <= relative_tolerance * rest;
      }
      if (pinned[static_cast<std::size_t>(v)] != 1) {
        // A moving pin, an unused vertex or a missing edge breaks the chain here.
        if (pinned[static_cast<std::size_t>(v)] == 2 || !mesh.is_used(v) || !edge_exists(k))
          start = -1;
        continue;
      }
      if (start >= 0 && k - start >= 2 && edges_at_rest &&
          std::abs((x.row(v) - x.row(vertex(start))).norm() - rest_length) <=
              relative_tolerance * rest_length) {
        for (Index i = start + 1; i < k; ++i) out.vertices.push_back(vertex(i));
        ++out.chains;
      }
      start = edge_exists(k) ? k : -1;
      rest_length = 0.0;
      edges_at_rest = true;
    }
  };
  for (Index j = 0; j < mesh.nv; ++j)
    scan(mesh.nu, [&](Index i) { return mesh.index(i, j); },
         [&](Index i) { return i + 1 < mesh.nu && mesh.warp_edge_cells(i, j) > 0; });
  for (Index i = 0; i < mesh.nu; ++i)
    scan(mesh.nv, [&](Index j) { return mesh.index(i, j); },
         [&](Index j) { return j + 1 < mesh.nv && mesh.weft_edge_cells(i, j) > 0; });
  std::sort(out.vertices.begin(), out.vertices.end());
  out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
  return out;
}

}  // namespace weft::sim
