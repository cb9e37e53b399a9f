#include "sim/grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/round_specimen.h"

namespace weft::sim {

std::vector<std::array<Index, 3>> ClothMesh::triangles() const {
  if (!has_grid()) return faces;
  std::vector<std::array<Index, 3>> tris;
  tris.reserve(2 * quads.size());
  for (const auto& q : quads) {
    tris.push_back({q[0], q[1], q[2]});
    tris.push_back({q[0], q[2], q[3]});
  }
  return tris;
}

void ClothMesh::require_grid(const std::string& what) const {
  if (!has_grid())
    throw std::invalid_argument(what + " needs the cloth's warp/weft grid; " + name() +
                                " has none (a triangle mesh; docs/meshes.md)");
}

Index ClothMesh::used_vertex_count() const {
  return static_cast<Index>(std::count(vertex_used.begin(), vertex_used.end(), true));
}

namespace {

// Whether the cell with centre (u, v), m, belongs to the specimen (SpecimenShape).
bool keeps_cell(const GridSpec& spec, double u_m, double v_m) {
  switch (spec.shape) {
    case SpecimenShape::rectangle:
      return true;
    case SpecimenShape::disc: {
      const double a = 0.5 * spec.size_u_m, b = 0.5 * spec.size_v_m;  // semi-axes, m
      const double x = (u_m - a) / a, y = (v_m - b) / b;
      return x * x + y * y <= 1.0;
    }
  }
  return true;
}


// make_grid with the cells `keep` selects (its size is #(nu−1)(nv−1), cell (i, j) at
// j·(nu−1) + i), or by the spec's shape when it is empty.
ClothMesh grid_of(const GridSpec& spec, const std::vector<bool>& keep) {
  check_grid_spec(spec);

  ClothMesh mesh;
  mesh.nu = spec.nu;
  mesh.nv = spec.nv;
  const Index n = spec.nu * spec.nv;
  const double du = spec.size_u_m / (spec.nu - 1);
  const double dv = spec.size_v_m / (spec.nv - 1);
  mesh.rest_positions.resize(n, 3);
  mesh.material_coords.resize(n);
  mesh.vertex_area_m2 = Eigen::VectorXd::Zero(n);
  for (Index j = 0; j < spec.nv; ++j) {
    for (Index i = 0; i < spec.nu; ++i) {
      const Index k = mesh.index(i, j);
      const Vec2 uv(i * du, j * dv);
      mesh.material_coords[k] = uv;
      mesh.rest_positions.row(k) = (spec.origin + uv.x() * spec.warp_axis + uv.y() * spec.weft_axis).transpose();
    }
  }
  // Each kept quad gives a quarter of its area to each corner: the lumped (area-weighted) mass
  // rule.
  const double quarter = 0.25 * du * dv;
  mesh.cell_kept.assign(static_cast<std::size_t>((spec.nu - 1) * (spec.nv - 1)), false);
  mesh.vertex_used.assign(static_cast<std::size_t>(n), false);
  for (Index j = 0; j + 1 < spec.nv; ++j) {
    for (Index i = 0; i + 1 < spec.nu; ++i) {
      if (keep.empty() ? !keeps_cell(spec, (i + 0.5) * du, (j + 0.5) * dv)
                       : !keep[static_cast<std::size_t>(j * (spec.nu - 1) + i)])
        continue;
      mesh.cell_kept[static_cast<std::size_t>(j * (spec.nu - 1) + i)] = true;
      const std::array<Index, 4> q{mesh.index(i, j), mesh.index(i + 1, j), mesh.index(i + 1, j + 1),
                                   mesh.index(i, j + 1)};
      mesh.quads.push_back(q);
      for (Index v : q) {
        mesh.vertex_area_m2[v] += quarter;
        mesh.vertex_used[static_cast<std::size_t>(v)] = true;
      }
    }
  }
  return mesh;
}

}  // namespace

void check_grid_spec(const GridSpec& spec) {
  if (spec.nu < 2 || spec.nv < 2)
    throw std::invalid_argument("grid resolution must be at least 2×2 vertices, got " +
                                std::to_string(spec.nu) + "×" + std::to_string(spec.nv));
  if (!(spec.size_u_m > 0.0) || !(spec.size_v_m > 0.0) || !std::isfinite(spec.size_u_m) ||
      !std::isfinite(spec.size_v_m))
    throw std::invalid_argument("grid size must be positive and finite");
}

ClothMesh make_grid(const GridSpec& spec) {
  if (spec.disc_edge == DiscEdge::smooth) {
    if (spec.shape != SpecimenShape::disc)
      throw std::invalid_argument(
          "a smooth edge applies to a disc; a rectangle's edges are grid lines");
    return make_round_specimen(spec);
  }
  return grid_of(spec, {});
}

ClothMesh make_grid_cells(const GridSpec& spec, const std::vector<bool>& cells) {
  if (static_cast<Index>(cells.size()) != std::max<Index>(0, (spec.nu - 1) * (spec.nv - 1)))
    throw std::invalid_argument("make_grid_cells: " + std::to_string(cells.size()) +
                                " cell flags for a grid of " + std::to_string(spec.nu) + "×" +
                                std::to_string(spec.nv) + " vertices");
  return grid_of(spec, cells);
}

}  // namespace weft::sim
