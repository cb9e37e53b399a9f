#include "sim/pins.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weft::sim {
namespace {

std::string range_text(Index count) { return "(0.." + std::to_string(count - 1) + ")"; }

// A selected vertex must belong to the specimen: unused vertices (outside a disc) cannot move.
std::vector<Index> used(Index v, const ClothMesh& mesh, const std::string& what) {
  if (!mesh.is_used(v))
    throw std::invalid_argument(what + " is not part of the cloth (outside the trimmed specimen)");
  return {v};
}

std::vector<Index> select(const PinVertex& p, const ClothMesh& mesh) {
  if (p.index < 0 || p.index >= mesh.vertex_count())
    throw std::invalid_argument("vertex " + std::to_string(p.index) + " is outside the mesh " +
                                range_text(mesh.vertex_count()));
  return used(p.index, mesh, "vertex " + std::to_string(p.index));
}

std::vector<Index> select(const PinGrid& p, const ClothMesh& mesh) {
  mesh.require_grid("a pin by grid vertex");
  if (p.i < 0 || p.i >= mesh.nu || p.j < 0 || p.j >= mesh.nv)
    throw std::invalid_argument("grid vertex [" + std::to_string(p.i) + ", " + std::to_string(p.j) +
                                "] is outside the mesh ([0.." + std::to_string(mesh.nu - 1) +
                                ", 0.." + std::to_string(mesh.nv - 1) + "])");
  return used(mesh.index(p.i, p.j), mesh,
              "grid vertex [" + std::to_string(p.i) + ", " + std::to_string(p.j) + "]");
}

std::vector<Index> select(const PinCorner& p, const ClothMesh& mesh) {
  mesh.require_grid("a pin by corner");
  const auto& names = corner_names();
  const auto it = std::find(names.begin(), names.end(), p.name);
  if (it == names.end()) {
    std::string choices;
    for (const auto& n : names) choices += (choices.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown corner '" + p.name + "' (choices: " + choices + ")");
  }
  const auto c = it - names.begin();  // bit 0: u at its maximum, bit 1: v at its maximum
  return used(mesh.index((c & 1) ? mesh.nu - 1 : 0, (c & 2) ? mesh.nv - 1 : 0), mesh,
              "corner " + p.name);
}

std::vector<Index> select(const PinRegion& p, const ClothMesh& mesh) {
  if (!(p.u0 <= p.u1) || !(p.v0 <= p.v1))
    throw std::invalid_argument("region bounds must be ordered (u0 ≤ u1, v0 ≤ v1)");
  std::vector<Index> out;
  if (!mesh.has_grid()) {
    Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
    for (Index v = 0; v < mesh.vertex_count(); ++v)
      if (mesh.is_used(v)) {
        lo = lo.cwiseMin(mesh.material_coords[static_cast<std::size_t>(v)]);
        hi = hi.cwiseMax(mesh.material_coords[static_cast<std::size_t>(v)]);
      }
    const Vec2 r0 = lo + Vec2(p.u0, p.v0).cwiseProduct(hi - lo);
    const Vec2 r1 = lo + Vec2(p.u1, p.v1).cwiseProduct(hi - lo);
    const Vec2 slack = Vec2::Constant(1e-9 * (hi - lo).norm());
    for (Index v = 0; v < mesh.vertex_count(); ++v) {
      const Vec2& m = mesh.material_coords[static_cast<std::size_t>(v)];
      if (mesh.is_used(v) && (m.array() >= (r0 - slack).array()).all() &&
          (m.array() <= (r1 + slack).array()).all())
        out.push_back(v);
    }
  }
  // Compare in grid units with a small tolerance so that a bound on a grid line includes it.
  const double eps = 1e-9;
  for (Index j = 0; j < mesh.nv && mesh.has_grid(); ++j) {
    const double v = static_cast<double>(j) / (mesh.nv - 1);
    if (v < p.v0 - eps || v > p.v1 + eps) continue;
    for (Index i = 0; i < mesh.nu; ++i) {
      const double u = static_cast<double>(i) / (mesh.nu - 1);
      if (u >= p.u0 - eps && u <= p.u1 + eps && mesh.is_used(mesh.index(i, j)))
        out.push_back(mesh.index(i, j));
    }
  }
  if (out.empty())
    throw std::invalid_argument("region u [" + std::to_string(p.u0) + ", " + std::to_string(p.u1) +
                                "], v [" + std::to_string(p.v0) + ", " + std::to_string(p.v1) +
                                "] contains no vertex of the cloth");
  return out;
}

std::vector<Index> select(const PinBox& p, const ClothMesh& mesh) {
  if (!(p.lo.array() <= p.hi.array()).all())
    throw std::invalid_argument("box bounds must be ordered (min ≤ max on each axis)");
  const int axes = p.world ? 3 : 2;
  std::vector<Index> out;
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    if (!mesh.is_used(v)) continue;
    const Vec3 x = p.world ? Vec3(mesh.start().row(v).transpose())
                           : Vec3(mesh.material_coords[static_cast<std::size_t>(v)].x(),
                                  mesh.material_coords[static_cast<std::size_t>(v)].y(), 0.0);
    bool inside = true;
    for (int k = 0; k < axes; ++k) inside = inside && x[k] >= p.lo[k] && x[k] <= p.hi[k];
    if (inside) out.push_back(v);
  }
  if (out.empty())
    throw std::invalid_argument(std::string(p.world ? "world" : "material") +
                                " box contains no vertex of the cloth");
  return out;
}

std::vector<Index> select(const PinVertexSet& p, const ClothMesh& mesh) {
  if (p.indices.empty()) throw std::invalid_argument(p.what + " selects no vertex of the cloth");
  for (const Index v : p.indices) select(PinVertex{v}, mesh);  // inside the mesh, and used
  return p.indices;
}

}  // namespace

const std::vector<std::string>& corner_names() {
  static const std::vector<std::string> names{"u0v0", "u1v0", "u0v1", "u1v1"};
  return names;
}

std::vector<Index> resolve_pins(const std::vector<PinSpec>& pins, const ClothMesh& mesh) {
  std::vector<Index> out;
  for (std::size_t k = 0; k < pins.size(); ++k) {
    try {
      const auto selected = std::visit([&](const auto& p) { return select(p, mesh); }, pins[k]);
      out.insert(out.end(), selected.begin(), selected.end());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("pin " + std::to_string(k) + ": " + e.what());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace weft::sim
