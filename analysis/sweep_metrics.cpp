#include "analysis/sweep_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weft::analysis {

sim::Vec3 position_at_material_point(const sim::ClothMesh& mesh, const sim::Matrix3X& x,
                                     const sim::Vec2& uv) {
  mesh.require_grid("comparing runs at material points (sweep distance)");
  if (mesh.nu < 2 || mesh.nv < 2 || x.rows() != mesh.vertex_count())
    throw std::invalid_argument("position_at_material_point: positions do not match the grid");
  // The grid's extent from its far corner's material coordinates (make_grid spaces vertices
  // evenly from (0, 0)).
  const sim::Vec2 size = mesh.material_coords[static_cast<std::size_t>(mesh.index(mesh.nu - 1, mesh.nv - 1))];
  const double s = std::clamp(uv.x() / size.x(), 0.0, 1.0) * (mesh.nu - 1);
  const double t = std::clamp(uv.y() / size.y(), 0.0, 1.0) * (mesh.nv - 1);
  const sim::Index i = std::min<sim::Index>(static_cast<sim::Index>(s), mesh.nu - 2);
  const sim::Index j = std::min<sim::Index>(static_cast<sim::Index>(t), mesh.nv - 2);
  const double a = s - i, b = t - j;  // in [0, 1] within the cell
  const auto p = [&](sim::Index di, sim::Index dj) -> sim::Vec3 {
    return x.row(mesh.index(i + di, j + dj)).transpose();
  };
  return (1 - a) * (1 - b) * p(0, 0) + a * (1 - b) * p(1, 0) + (1 - a) * b * p(0, 1) +
         a * b * p(1, 1);
}

double rms_distance_m(const sim::ClothMesh& reference_mesh, const sim::Matrix3X& reference_x,
                      const sim::ClothMesh& mesh, const sim::Matrix3X& x) {
  if (x.rows() != mesh.vertex_count() || x.rows() == 0)
    throw std::invalid_argument("rms_distance_m: positions do not match the mesh");
  double sum_m2 = 0.0;
  // The same grid: vertex to vertex, without the rounding of the interpolation weights (so a
  // run compared with itself is exactly 0 apart).
  if (reference_mesh.nu == mesh.nu && reference_mesh.nv == mesh.nv &&
      reference_mesh.material_coords == mesh.material_coords && reference_x.rows() == x.rows()) {
    return std::sqrt((x - reference_x).squaredNorm() / static_cast<double>(x.rows()));
  }
  for (sim::Index k = 0; k < mesh.vertex_count(); ++k) {
    const sim::Vec3 ref = position_at_material_point(
        reference_mesh, reference_x, mesh.material_coords[static_cast<std::size_t>(k)]);
    sum_m2 += (x.row(k).transpose() - ref).squaredNorm();
  }
  return std::sqrt(sum_m2 / static_cast<double>(x.rows()));
}

long Mask::count() const { return static_cast<long>(std::count(cells.begin(), cells.end(), true)); }

OrthoView ortho_view(const sim::Vec3& view_direction, const sim::Vec3& up_hint) {
  const sim::Vec3 forward = view_direction.normalized();
  const sim::Vec3 right = forward.cross(up_hint);
  if (!(right.norm() > 1e-9 * up_hint.norm()))
    throw std::invalid_argument("ortho_view: the view direction is parallel to the up hint");
  OrthoView view;
  view.right = right.normalized();
  view.up = view.right.cross(forward);
  return view;
}

Window joint_window(const OrthoView& view, const sim::Matrix3X& a, const sim::Matrix3X& b,
                    double margin) {
  double u_min = INFINITY, u_max = -INFINITY, v_min = INFINITY, v_max = -INFINITY;
  for (const sim::Matrix3X* x : {&a, &b}) {
    for (Eigen::Index k = 0; k < x->rows(); ++k) {
      const double u = x->row(k).dot(view.right.transpose());
      const double v = x->row(k).dot(view.up.transpose());
      u_min = std::min(u_min, u);
      u_max = std::max(u_max, u);
      v_min = std::min(v_min, v);
      v_max = std::max(v_max, v);
    }
  }
  Window w;
  if (!(u_max >= u_min && v_max >= v_min)) return w;  // no points
  const double side = std::max({u_max - u_min, v_max - v_min, 1e-9});
  w.side_m = side * (1.0 + 2.0 * margin);
  w.u0 = 0.5 * (u_min + u_max) - 0.5 * w.side_m;
  w.v0 = 0.5 * (v_min + v_max) - 0.5 * w.side_m;
  return w;
}

Mask silhouette(const std::vector<std::array<sim::Index, 3>>& triangles, const sim::Matrix3X& x,
                const OrthoView& view, const Window& window, int n) {
  Mask mask;
  mask.width = mask.height = n;
  mask.cells.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), false);
  const double cell_m = window.side_m / n;
  // Image coordinates in cells: column c's centre at c + ½ from the left, row r's at r + ½
  // from the top.
  const auto to_cells = [&](sim::Index k) -> Eigen::Vector2d {
    const double u = x.row(k).dot(view.right.transpose());
    const double v = x.row(k).dot(view.up.transpose());
    return {(u - window.u0) / cell_m, (window.v0 + window.side_m - v) / cell_m};
  };
  for (const auto& tri : triangles) {
    const Eigen::Vector2d p0 = to_cells(tri[0]), p1 = to_cells(tri[1]), p2 = to_cells(tri[2]);
    const double area2 = (p1 - p0).x() * (p2 - p0).y() - (p1 - p0).y() * (p2 - p0).x();
    if (area2 == 0.0 || !std::isfinite(area2)) continue;  // edge-on: covers no area
    const double sign = area2 > 0 ? 1.0 : -1.0;
    const int c_lo = std::max(0, static_cast<int>(std::floor(std::min({p0.x(), p1.x(), p2.x()}))));
    const int c_hi = std::min(n - 1, static_cast<int>(std::floor(std::max({p0.x(), p1.x(), p2.x()}))));
    const int r_lo = std::max(0, static_cast<int>(std::floor(std::min({p0.y(), p1.y(), p2.y()}))));
    const int r_hi = std::min(n - 1, static_cast<int>(std::floor(std::max({p0.y(), p1.y(), p2.y()}))));
    // Edge function of a → b at q, positive on the triangle's side for either orientation.
    const auto edge = [sign](const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const Eigen::Vector2d& q) {
      return sign * ((b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x()));
    };
    for (int r = r_lo; r <= r_hi; ++r) {
      for (int c = c_lo; c <= c_hi; ++c) {
        const Eigen::Vector2d q(c + 0.5, r + 0.5);
        if (edge(p0, p1, q) >= 0 && edge(p1, p2, q) >= 0 && edge(p2, p0, q) >= 0)
          mask.cells[static_cast<std::size_t>(r * n + c)] = true;
      }
    }
  }
  return mask;
}

double silhouette_difference(const Mask& a, const Mask& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("silhouette_difference: masks of different sizes");
  long either = 0, one = 0;
  for (std::size_t k = 0; k < a.cells.size(); ++k) {
    either += a.cells[k] || b.cells[k];
    one += a.cells[k] != b.cells[k];
  }
  return either == 0 ? 0.0 : static_cast<double>(one) / static_cast<double>(either);
}

std::vector<bool> pareto_optimal(const std::vector<double>& time_s,
                                 const std::vector<double>& error,
                                 const std::vector<bool>& eligible) {
  const std::size_t n = time_s.size();
  if (error.size() != n || eligible.size() != n)
    throw std::invalid_argument("pareto_optimal: inputs of different lengths");
  std::vector<bool> optimal(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!eligible[i]) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j) {
      if (j == i || !eligible[j]) continue;
      dominated = time_s[j] <= time_s[i] && error[j] <= error[i] &&
                  (time_s[j] < time_s[i] || error[j] < error[i]);
    }
    optimal[i] = !dominated;
  }
  return optimal;
}

}  // namespace weft::analysis
