// Cloth meshes from flat patterns (see triangle_cloth.h).

#include "sim/triangle_cloth.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace weft::sim {
namespace {

using Face = std::vector<Index>;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Twice the signed area of a polygon in material coordinates (shoelace).
double twice_signed_area(const std::vector<Vec2>& m, const Face& f) {
  double sum = 0.0;
  for (std::size_t c = 0; c < f.size(); ++c)
    sum += cross(m[static_cast<std::size_t>(f[c])], m[static_cast<std::size_t>(f[(c + 1) % f.size()])]);
  return sum;
}

std::string face_text(std::size_t f, const Face& face) {
  std::string corners;
  for (const Index v : face) corners += (corners.empty() ? "" : ", ") + std::to_string(v);
  return "face " + std::to_string(f) + " (vertices " + corners + ")";
}

// The faces turned counter-clockwise in material coordinates, checked (triangle_cloth.h).
std::vector<Face> oriented_faces(const ClothPattern& p) {
  const auto& m = p.material_coords;
  const Index n = static_cast<Index>(m.size());
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (const Vec2& x : m) {
    if (!x.allFinite())
      throw std::invalid_argument("a vertex's material coordinates are not finite");
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double min_twice_area = 2e-10 * (hi - lo).squaredNorm();
  std::vector<Face> faces;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    Face face = p.faces[f];
    for (const Index v : face)
      if (v < 0 || v >= n)
        throw std::invalid_argument(face_text(f, face) + " refers to a vertex outside 0.." +
                                    std::to_string(n - 1));
    const double a2 = twice_signed_area(m, face);
    if (!(std::abs(a2) > min_twice_area))
      throw std::invalid_argument(face_text(f, face) + " has zero area in material coordinates "
                                  "(a degenerate triangle, or a face seen edge-on by the flattening)");
    if (a2 < 0.0) std::reverse(face.begin(), face.end());
    // Convex: every fan triangle turns the same way as the polygon.
    for (std::size_t c = 1; c + 1 < face.size(); ++c) {
      const Vec2& o = m[static_cast<std::size_t>(face[0])];
      if (!(cross(m[static_cast<std::size_t>(face[c])] - o, m[static_cast<std::size_t>(face[c + 1])] - o) > 0.0))
        throw std::invalid_argument(face_text(f, p.faces[f]) + " is not convex in material "
                                    "coordinates (split it into triangles in the file)");
    }
    faces.push_back(std::move(face));
  }
  // Each undirected edge: how many faces have it; each directed edge at most once.
  std::map<std::pair<Index, Index>, int> uses;
  std::map<std::pair<Index, Index>, std::size_t> directed;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Face& face = faces[f];
    for (std::size_t c = 0; c < face.size(); ++c) {
      const Index a = face[c], b = face[(c + 1) % face.size()];
      if (++uses[std::minmax(a, b)] == 3)
        throw std::invalid_argument("edge " + std::to_string(std::min(a, b)) + "–" +
                                    std::to_string(std::max(a, b)) +
                                    " is shared by more than two faces (a non-manifold mesh)");
      const auto [at, added] = directed.emplace(std::make_pair(a, b), f);
      if (!added)
        throw std::invalid_argument(
            face_text(at->second, p.faces[at->second]) + " and " + face_text(f, p.faces[f]) +
            " overlap in material coordinates at edge " + std::to_string(a) + "–" +
            std::to_string(b) + " (a fold in the UV map or the flattening)");
    }
  }
  return faces;
}

// The lattice of a quad grid in material coordinates, when the faces are one (triangle_cloth.h).
std::optional<ClothMesh> recognised_grid(const ClothPattern& p, const std::vector<Face>& faces) {
  const auto& m = p.material_coords;
  for (const Face& f : faces)
    if (f.size() != 4) return std::nullopt;
  // The spacing from the first quad, read from the corner whose two sides run along +u, +v.
  const Face& q = faces.front();
  double du = 0.0, dv = 0.0;
  for (std::size_t r = 0; r < 4 && du == 0.0; ++r) {
    const Vec2 e1 = m[static_cast<std::size_t>(q[(r + 1) % 4])] - m[static_cast<std::size_t>(q[r])];
    const Vec2 e2 = m[static_cast<std::size_t>(q[(r + 3) % 4])] - m[static_cast<std::size_t>(q[r])];
    if (e1.x() > 0.0 && std::abs(e1.y()) <= 1e-6 * e1.x() && e2.y() > 0.0 &&
        std::abs(e2.x()) <= 1e-6 * e2.y()) {
      du = e1.x();
      dv = e2.y();
    }
  }
  if (du == 0.0) return std::nullopt;
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (const Face& f : faces)
    for (const Index v : f) {
      lo = lo.cwiseMin(m[static_cast<std::size_t>(v)]);
      hi = hi.cwiseMax(m[static_cast<std::size_t>(v)]);
    }
  GridSpec spec;
  spec.nu = static_cast<Index>(std::lround((hi.x() - lo.x()) / du)) + 1;
  spec.nv = static_cast<Index>(std::lround((hi.y() - lo.y()) / dv)) + 1;
  if (spec.nu < 2 || spec.nv < 2 || spec.nu > 65536 || spec.nv > 65536) return std::nullopt;
  spec.size_u_m = hi.x() - lo.x();
  spec.size_v_m = hi.y() - lo.y();
  du = spec.size_u_m / static_cast<double>(spec.nu - 1);
  dv = spec.size_v_m / static_cast<double>(spec.nv - 1);
  // Each used vertex on a lattice point (within 1e-4 of a cell: the file's single precision).
  const Index n = static_cast<Index>(m.size());
  std::vector<Index> lattice(static_cast<std::size_t>(n), -1);
  std::vector<Index> vertex_at(static_cast<std::size_t>(spec.nu * spec.nv), -1);
  for (const Face& f : faces)
    for (const Index v : f) {
      if (lattice[static_cast<std::size_t>(v)] >= 0) continue;
      const double s = (m[static_cast<std::size_t>(v)].x() - lo.x()) / du;
      const double t = (m[static_cast<std::size_t>(v)].y() - lo.y()) / dv;
      const double i = std::round(s), j = std::round(t);
      if (std::abs(s - i) > 1e-4 || std::abs(t - j) > 1e-4) return std::nullopt;
      const Index k = static_cast<Index>(j) * spec.nu + static_cast<Index>(i);
      if (vertex_at[static_cast<std::size_t>(k)] >= 0) return std::nullopt;  // two on one point
      vertex_at[static_cast<std::size_t>(k)] = v;
      lattice[static_cast<std::size_t>(v)] = k;
    }
  // Each quad a cell: (i,j) (i+1,j) (i+1,j+1) (i,j+1) from one of its corners.
  std::vector<bool> cells(static_cast<std::size_t>((spec.nu - 1) * (spec.nv - 1)), false);
  for (const Face& f : faces) {
    bool matched = false;
    for (std::size_t r = 0; r < 4 && !matched; ++r) {
      const Index k = lattice[static_cast<std::size_t>(f[r])];
      const Index i = k % spec.nu, j = k / spec.nu;
      if (i + 1 >= spec.nu || j + 1 >= spec.nv) continue;
      matched = lattice[static_cast<std::size_t>(f[(r + 1) % 4])] == k + 1 &&
                lattice[static_cast<std::size_t>(f[(r + 2) % 4])] == k + spec.nu + 1 &&
                lattice[static_cast<std::size_t>(f[(r + 3) % 4])] == k + spec.nu;
      if (matched) cells[static_cast<std::size_t>(j * (spec.nu - 1) + i)] = true;
    }
    if (!matched) return std::nullopt;
  }
  spec.origin = p.origin;
  spec.warp_axis = p.warp_axis;
  spec.weft_axis = p.weft_axis;
  ClothMesh mesh = make_grid_cells(spec, cells);
  mesh.start_positions = mesh.rest_positions;  // lattice points of no quad stay at rest
  for (Index v = 0; v < n; ++v)
    if (lattice[static_cast<std::size_t>(v)] >= 0)
      mesh.start_positions.row(lattice[static_cast<std::size_t>(v)]) = p.start_positions.row(v);
  return mesh;
}

}  // namespace

ClothMesh make_pattern_cloth(const ClothPattern& p) {
  const Index n = static_cast<Index>(p.material_coords.size());
  if (p.start_positions.rows() != n)
    throw std::invalid_argument("pattern: " + std::to_string(n) + " material coordinates for " +
                                std::to_string(p.start_positions.rows()) + " vertices");
  if (!p.start_positions.allFinite())
    throw std::invalid_argument("a vertex's position is not finite");
  if (p.faces.empty()) throw std::invalid_argument("the mesh has no faces");
  const std::vector<Face> faces = oriented_faces(p);
  if (std::optional<ClothMesh> grid = recognised_grid(p, faces)) {
    grid->source = p.source;
    return std::move(*grid);
  }
  ClothMesh mesh;
  mesh.source = p.source;
  mesh.material_coords = p.material_coords;
  mesh.start_positions = p.start_positions;
  mesh.rest_positions.resize(n, 3);
  for (Index v = 0; v < n; ++v) {
    const Vec2& uv = p.material_coords[static_cast<std::size_t>(v)];
    mesh.rest_positions.row(v) = (p.origin + uv.x() * p.warp_axis + uv.y() * p.weft_axis).transpose();
  }
  mesh.vertex_area_m2 = Eigen::VectorXd::Zero(n);
  mesh.vertex_used.assign(static_cast<std::size_t>(n), false);
  for (const Face& f : faces)
    for (std::size_t c = 1; c + 1 < f.size(); ++c) {
      const std::array<Index, 3> t{f[0], f[c], f[c + 1]};
      mesh.faces.push_back(t);
      const Vec2& o = p.material_coords[static_cast<std::size_t>(t[0])];
      const double third = cross(p.material_coords[static_cast<std::size_t>(t[1])] - o,
                                 p.material_coords[static_cast<std::size_t>(t[2])] - o) / 6.0;
      for (const Index v : t) {
        mesh.vertex_area_m2[v] += third;
        mesh.vertex_used[static_cast<std::size_t>(v)] = true;
      }
    }
  return mesh;
}

}  // namespace weft::sim
