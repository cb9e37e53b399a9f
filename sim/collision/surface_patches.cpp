// Patches of the cloth with bounding boxes and normal cones; see surface_patches.h.

#include "sim/collision/surface_patches.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/check.h"
#include "base/constants.h"


namespace weft::sim {
namespace {

Aabb merged(const Aabb& a, const Aabb& b) { return {a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi)}; }

// Where each triangle falls in a grid of patches: its patch's (column, row), and the grid's size.
struct PatchCells {
  std::vector<std::array<Index, 2>> cell_of;  // per triangle
  Index patches_u = 0, patches_v = 0;
};

// On a grid: patches of cells_per_side² grid cells.
PatchCells patch_cells_on_grid(const ClothMesh& mesh,
                               const std::vector<std::array<Index, 3>>& triangles,
                               Index cells_per_side) {
  WEFT_CHECK(triangles.size() == 2 * mesh.quads.size(),
             "surface patches: expected the mesh's " + std::to_string(2 * mesh.quads.size()) +
                 " triangles, got " + std::to_string(triangles.size()));
  PatchCells cells;
  cells.cell_of.resize(triangles.size());
  cells.patches_u = (mesh.nu - 2) / cells_per_side + 1;
  cells.patches_v = (mesh.nv - 2) / cells_per_side + 1;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& quad = mesh.quads[t / 2];
    WEFT_CHECK(triangles[t][0] == quad[0], "surface patches: triangle " + std::to_string(t) +
                                               " is not from grid cell " + std::to_string(t / 2));
    cells.cell_of[t] = {(quad[0] % mesh.nu) / cells_per_side, (quad[0] / mesh.nu) / cells_per_side};
  }
  return cells;
}

// On a mesh without a grid: squares of side cells_per_side mean material edge lengths in
// material coordinates, each holding the triangles whose centroids lie in it.
PatchCells patch_cells_on_material_squares(const ClothMesh& mesh,
                                           const std::vector<std::array<Index, 3>>& triangles,
                                           Index cells_per_side) {
  const auto uv = [&](Index v) { return mesh.material_coords[static_cast<std::size_t>(v)]; };
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double edge_sum = 0.0;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(uv(t[k]));
      hi = hi.cwiseMax(uv(t[k]));
      edge_sum += (uv(t[(k + 1) % 3]) - uv(t[k])).norm();
    }
  const double side = cells_per_side * edge_sum / std::max(1.0, 3.0 * static_cast<double>(triangles.size()));
  const auto bucket = [&](double d) { return static_cast<Index>(std::floor(d / side)); };
  PatchCells cells;
  cells.cell_of.resize(triangles.size());
  cells.patches_u = bucket(hi.x() - lo.x()) + 1;
  cells.patches_v = bucket(hi.y() - lo.y()) + 1;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Vec2 c = (uv(triangles[t][0]) + uv(triangles[t][1]) + uv(triangles[t][2])) / 3.0 - lo;
    cells.cell_of[t] = {std::min(bucket(c.x()), cells.patches_u - 1),
                        std::min(bucket(c.y()), cells.patches_v - 1)};
  }
  return cells;
}

// Ownership: each vertex, resp. edge, goes to the patch of the first triangle that has it.
void assign_patch_ownership(const std::vector<std::array<Index, 3>>& triangles,
                            const std::vector<std::array<Index, 2>>& edges, Index vertex_count,
                            const std::vector<Index>& patch_of_triangle,
                            std::vector<SurfacePatch>& patches) {
  std::vector<bool> vertex_owned(static_cast<std::size_t>(vertex_count), false);
  std::vector<bool> edge_owned(edges.size(), false);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    SurfacePatch& patch = patches[static_cast<std::size_t>(patch_of_triangle[t])];
    const auto& tri = triangles[t];
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tri[k]);
      if (!vertex_owned[v]) {
        vertex_owned[v] = true;
        patch.owned_vertices.push_back(tri[k]);
      }
      const std::array<Index, 2> edge{std::min(tri[k], tri[(k + 1) % 3]),
                                      std::max(tri[k], tri[(k + 1) % 3])};
      const auto it = std::lower_bound(edges.begin(), edges.end(), edge);
      WEFT_CHECK(it != edges.end() && *it == edge,
                 "surface patches: edge list lacks an edge of triangle " + std::to_string(t));
      const auto e = static_cast<std::size_t>(it - edges.begin());
      if (!edge_owned[e]) {
        edge_owned[e] = true;
        patch.owned_edges.push_back(static_cast<Index>(e));
      }
    }
  }
}

// Sorts each patch's owned vertices and edges, and lists the vertices of its triangles.
void sort_patch_vertex_lists(const std::vector<std::array<Index, 3>>& triangles,
                             std::vector<SurfacePatch>& patches) {
  for (SurfacePatch& patch : patches) {
    std::sort(patch.owned_vertices.begin(), patch.owned_vertices.end());
    std::sort(patch.owned_edges.begin(), patch.owned_edges.end());
    for (const Index t : patch.triangles) {
      const auto& tri = triangles[static_cast<std::size_t>(t)];
      patch.vertices.insert(patch.vertices.end(), tri.begin(), tri.end());
    }
    std::sort(patch.vertices.begin(), patch.vertices.end());
    patch.vertices.erase(std::unique(patch.vertices.begin(), patch.vertices.end()),
                         patch.vertices.end());
  }
}

// The inverse of a triangle's rest edge matrix in a frame of its own plane. A degenerate rest
// triangle gets a zero inverse: least stretch 0, nothing culled.
Eigen::Matrix2d rest_edge_frame_inverse(const Matrix3X& rest_positions,
                                        const std::array<Index, 3>& tri) {
  const Vec3 e1 = vertex(rest_positions, tri[1]) - vertex(rest_positions, tri[0]);
  const Vec3 e2 = vertex(rest_positions, tri[2]) - vertex(rest_positions, tri[0]);
  const Vec3 u = e1.normalized(), v = (e1.cross(e2)).cross(e1).normalized();
  Eigen::Matrix2d rest;
  rest << u.dot(e1), u.dot(e2), v.dot(e1), v.dot(e2);
  return std::abs(rest.determinant()) > 0.0 && rest.allFinite() ? Eigen::Matrix2d(rest.inverse())
                                                                 : Eigen::Matrix2d::Zero();
}

// The smallest singular value of a 3×2 matrix: the root of the smaller eigenvalue of FᵀF.
double least_singular_value(const Eigen::Matrix<double, 3, 2>& f) {
  const double p = f.col(0).squaredNorm(), q = f.col(1).squaredNorm(), r = f.col(0).dot(f.col(1));
  const double half_gap = 0.5 * (p - q);
  return std::sqrt(std::max(0.0, 0.5 * (p + q) - std::sqrt(half_gap * half_gap + r * r)));
}

// One triangle's part of its patch's fit (SurfacePatches::refit, refit_swept).
struct TriangleFit {
  Aabb box;
  Vec3 normal_sum;  // added to the patch's
  double least_stretch;
  bool degenerate;
};

// Refits a patch from fit(t), t each of its triangles: its box, normal sum and least stretch.
// Returns whether a triangle is degenerate.
template <class Fit>
bool fit_patch(SurfacePatch& patch, Fit&& fit) {
  patch.normal_sum.setZero();
  patch.least_stretch = std::numeric_limits<double>::infinity();
  bool degenerate = false;
  for (std::size_t k = 0; k < patch.triangles.size(); ++k) {
    const TriangleFit f = fit(static_cast<std::size_t>(patch.triangles[k]));
    patch.box = k == 0 ? f.box : merged(patch.box, f.box);
    patch.normal_sum += f.normal_sum;
    patch.least_stretch = std::min(patch.least_stretch, f.least_stretch);
    degenerate = degenerate || f.degenerate;
  }
  return degenerate;
}

}  // namespace

SurfacePatches::SurfacePatches(const ClothMesh& mesh,
                               const std::vector<std::array<Index, 3>>& triangles,
                               const std::vector<std::array<Index, 2>>& edges, Index cells_per_side)
    : m_triangles(triangles) {
  // What SelfCollision hands in: the mesh's own triangles and unique edges.
  WEFT_CHECK(cells_per_side >= 1,
             "surface patches: cells per side " + std::to_string(cells_per_side));
  // A grid: patches of grid cells. A mesh without one: squares of material coordinates, and
  // no culling by the normal cones (surface_patches.h).
  const PatchCells cells = mesh.has_grid()
                               ? patch_cells_on_grid(mesh, triangles, cells_per_side)
                               : patch_cells_on_material_squares(mesh, triangles, cells_per_side);
  m_cone_culling = mesh.has_grid();
  m_patches_u = cells.patches_u;
  m_patch_of_grid.assign(static_cast<std::size_t>(cells.patches_u * cells.patches_v), -1);
  std::vector<Index> patch_of_triangle(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const std::array<Index, 2> grid = cells.cell_of[t];
    Index& p = m_patch_of_grid[static_cast<std::size_t>(grid[1] * cells.patches_u + grid[0])];
    if (p < 0) {
      p = static_cast<Index>(m_patches.size());
      m_patches.emplace_back();
      m_patches.back().grid = grid;
    }
    m_patches[static_cast<std::size_t>(p)].triangles.push_back(static_cast<Index>(t));
    patch_of_triangle[t] = p;
  }
  assign_patch_ownership(triangles, edges, mesh.vertex_count(), patch_of_triangle, m_patches);
  sort_patch_vertex_lists(triangles, m_patches);
  m_normals.resize(m_triangles.size());
  m_rest_inverse.resize(m_triangles.size());
  for (std::size_t t = 0; t < m_triangles.size(); ++t)
    m_rest_inverse[t] = rest_edge_frame_inverse(mesh.rest_positions, m_triangles[t]);
  refit(mesh.rest_positions);
  for (SurfacePatch& patch : m_patches) patch.rest_box = patch.box;
}

void SurfacePatches::refit(const Matrix3X& x) { refit(x, 0, m_patches.size()); }

void SurfacePatches::refit(const Matrix3X& x, std::size_t first, std::size_t end) {
  for (std::size_t i = first; i < end; ++i) {
    const bool degenerate = fit_patch(m_patches[i], [&](std::size_t t) {
      const auto& tri = m_triangles[t];
      const Vec3 a = vertex(x, tri[0]), b = vertex(x, tri[1]), c = vertex(x, tri[2]);
      m_normals[t] = (b - a).cross(c - a);
      Eigen::Matrix<double, 3, 2> edges;
      edges << b - a, c - a;
      return TriangleFit{bounding_box(a, b, c), m_normals[t],
                         least_singular_value(edges * m_rest_inverse[t]),
                         !(m_normals[t].squaredNorm() > 0.0)};
    });
    set_cone(m_patches[i], degenerate, 1);
  }
}

void SurfacePatches::refit_swept(const Matrix3X& x_start, const Matrix3X& x,
                                 const std::vector<char>* only) {
  m_normals.resize(3 * m_triangles.size());
  for (std::size_t i = 0; i < m_patches.size(); ++i) {
    if (only && !(*only)[i]) continue;
    const bool degenerate = fit_patch(m_patches[i], [&](std::size_t t) {
      const auto& tri = m_triangles[t];
      const Vec3 a0 = vertex(x_start, tri[0]), a1 = vertex(x, tri[0]);
      const Vec3 e0 = vertex(x_start, tri[1]) - a0, f0 = vertex(x_start, tri[2]) - a0;
      const Vec3 e1 = vertex(x, tri[1]) - a1, f1 = vertex(x, tri[2]) - a1;
      const Aabb box = merged(bounding_box(a0, vertex(x_start, tri[1]), vertex(x_start, tri[2])),
                              bounding_box(a1, vertex(x, tri[1]), vertex(x, tri[2])));
      // n(t) = (1−t)² n₀ + 2t(1−t) n_mid + t² n₁ along the straight paths: a positive
      // combination of the three, so within any convex cone that holds them.
      Vec3* n = &m_normals[3 * t];
      n[0] = e0.cross(f0);
      n[1] = 0.5 * (e0.cross(f1) + e1.cross(f0));
      n[2] = e1.cross(f1);
      // F(t) = F₀ + t (F₁ − F₀): by Weyl's inequality σ_min(F(t)) ≥ σ_min(F₀) − t‖ΔF‖ and
      // ≥ σ_min(F₁) − (1−t)‖ΔF‖, so at least (σ₀ + σ₁ − ‖ΔF‖)/2 over the step.
      Eigen::Matrix<double, 3, 2> start_edges, end_edges;
      start_edges << e0, f0;
      end_edges << e1, f1;
      const Eigen::Matrix<double, 3, 2> F0 = start_edges * m_rest_inverse[t];
      const Eigen::Matrix<double, 3, 2> F1 = end_edges * m_rest_inverse[t];
      const double least =
          0.5 * (least_singular_value(F0) + least_singular_value(F1) - (F1 - F0).norm());
      return TriangleFit{box, n[0] + n[2], std::max(0.0, least),
                         !(n[0].squaredNorm() > 0.0) || !(n[2].squaredNorm() > 0.0)};
    });
    set_cone(m_patches[i], degenerate, 3);
  }
}

// The patch's cone: its axis, the normalized normal_sum, and the largest angle between it and
// the normals its triangles keep in m_normals (normals_per_triangle each; a zero one is left
// out: it adds nothing to a positive combination). π when a triangle is degenerate.
void SurfacePatches::set_cone(SurfacePatch& patch, bool degenerate, int normals_per_triangle) {
  const double length = patch.normal_sum.norm();
  if (degenerate || !(length > 0.0)) {
    patch.cone_angle_rad = base::kPi;
    return;
  }
  const Vec3 axis = patch.normal_sum / length;
  double cos_min = 1.0;
  for (const Index t : patch.triangles)
    for (int k = 0; k < normals_per_triangle; ++k) {
      const Vec3& n = m_normals[static_cast<std::size_t>(normals_per_triangle * t + k)];
      const double n_length = n.norm();
      if (n_length > 0.0) cos_min = std::min(cos_min, axis.dot(n) / n_length);
    }
  patch.cone_angle_rad = std::acos(std::clamp(cos_min, -1.0, 1.0));
}

double ConeCulling::flat_angle_rad(double reach_m, double least_stretch) const {
  const double cos_flat = reach_m / (least_stretch * exclusion_m);
  if (!(exclusion_m > 0.0) || !(cos_flat < 1.0)) return 0.0;  // also for a stretch of 0
  return std::min(std::acos(cos_flat), max_angle_rad);
}

bool SurfacePatches::neighbours(Index p, Index q) const {
  const auto& a = (*this)[p].grid;
  const auto& b = (*this)[q].grid;
  return p != q && std::abs(a[0] - b[0]) <= 1 && std::abs(a[1] - b[1]) <= 1;
}

bool SurfacePatches::union_flat(Index p, Index q, const std::vector<double>& flat_angles_rad) const {
  const auto& a = (*this)[p].grid;
  const auto& b = (*this)[q].grid;
  std::array<Index, 4> members{};  // neighbours span at most 2 × 2 patches
  std::size_t count = 0;
  Vec3 sum = Vec3::Zero();
  double flat_rad = base::kPi;
  for (Index j = std::min(a[1], b[1]); j <= std::max(a[1], b[1]); ++j)
    for (Index i = std::min(a[0], b[0]); i <= std::max(a[0], b[0]); ++i) {
      const Index k = m_patch_of_grid[static_cast<std::size_t>(j * m_patches_u + i)];
      if (k < 0) return false;
      members[count++] = k;
      sum += (*this)[k].normal_sum;
      flat_rad = std::min(flat_rad, flat_angles_rad[static_cast<std::size_t>(k)]);
    }
  const double length = sum.norm();
  if (!(length > 0.0)) return false;
  // A member's normals lie within θ_axis + θ_cone of the union's axis, θ_axis the angle
  // between the two axes: below the flat angle when cos θ_axis > cos(flat − θ_cone).
  for (std::size_t m = 0; m < count; ++m) {
    const SurfacePatch& member = (*this)[members[m]];
    const double member_length = member.normal_sum.norm();
    const double room_rad = flat_rad - member.cone_angle_rad;
    if (!(room_rad > 0.0) || !(member_length > 0.0) ||
        !(sum.dot(member.normal_sum) > std::cos(room_rad) * length * member_length))
      return false;
  }
  return true;
}

void SurfacePatches::near_pairs(double reach_m, const ConeCulling& culling,
                                std::vector<std::array<Index, 2>>& pairs,
                                const std::vector<char>* wanted) {
  pairs_within(reach_m, reach_m, culling, m_within, wanted);
  pairs.clear();
  for (const PatchPair& pair : m_within)
    if (!pair.culled) pairs.push_back(pair.ids);
}

void SurfacePatches::pairs_within(double watch_m, double reach_m, const ConeCulling& culling,
                                  std::vector<PatchPair>& pairs, const std::vector<char>* wanted) {
  const auto is_wanted = [&](Index p) { return !wanted || (*wanted)[static_cast<std::size_t>(p)]; };
  pairs.clear();
  // The boxes grown by half the watch distance overlap where the boxes come within it along
  // every axis: found on a grid (box_pairs.h), where a sweep along one axis would meet every
  // patch across the draped cloth at that coordinate.
  m_grown_boxes.resize(m_patches.size());
  for (std::size_t i = 0; i < m_patches.size(); ++i)
    m_grown_boxes[i] = inflated(m_patches[i].box, 0.5 * watch_m);
  m_box_pairs.find(m_grown_boxes, m_overlaps);
  // Each patch's flat angle, by its least stretch.
  m_flat_angles_rad.resize(m_patches.size());
  bool any_flat = false;
  for (std::size_t i = 0; i < m_patches.size(); ++i) {
    m_flat_angles_rad[i] =
        m_cone_culling ? culling.flat_angle_rad(reach_m, m_patches[i].least_stretch) : 0.0;
    any_flat = any_flat || m_flat_angles_rad[i] > 0.0;
  }
  // The patches against themselves and the overlapping pairs, in the order of their ids.
  auto overlap = m_overlaps.begin();
  for (std::size_t i = 0; i < m_patches.size(); ++i) {
    const auto p = static_cast<Index>(i);
    const SurfacePatch& a = m_patches[i];
    if (is_wanted(p)) pairs.push_back({{p, p}, 0.0, a.cone_angle_rad < m_flat_angles_rad[i]});
    for (; overlap != m_overlaps.end() && (*overlap)[0] == p; ++overlap) {
      const Index q = (*overlap)[1];
      if (!is_wanted(p) && !is_wanted(q)) continue;
      const SurfacePatch& b = m_patches[static_cast<std::size_t>(q)];
      const double gap_m =
          std::max(0.0, (b.box.lo - a.box.hi).cwiseMax(a.box.lo - b.box.hi).maxCoeff());
      const bool culled = any_flat && gap_m <= reach_m && neighbours(p, q) &&
                          union_flat(p, q, m_flat_angles_rad);
      pairs.push_back({{p, q}, gap_m, culled});
    }
  }
}

void SurfacePatches::motions(const Matrix3X& x, const Matrix3X& reference,
                             std::vector<PatchMotion>& motions) const {
  motions.resize(m_patches.size());
  for (std::size_t i = 0; i < m_patches.size(); ++i) {
    const std::vector<Index>& vertices = m_patches[i].vertices;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Index v : vertices) {
      const Vec3 d = (x.row(v) - reference.row(v)).transpose();
      lo = lo.cwiseMin(d);
      hi = hi.cwiseMax(d);
    }
    PatchMotion& m = motions[i];
    m.centre = 0.5 * (lo + hi);
    double spread2 = 0.0;
    for (const Index v : vertices)
      spread2 = std::max(spread2, (x.row(v) - reference.row(v) - m.centre.transpose()).squaredNorm());
    m.spread_m = std::sqrt(spread2);
  }
}

}  // namespace weft::sim
