#include "sim/remesh/point_locator.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "sim/remesh/mesh_topology.h"

namespace weft::sim::remesh {

PointLocator::PointLocator(const Matrix2X& material, const Triangles& triangles)
    : m_material(material), m_triangles(triangles) {
  const Vec2 lo = material.colwise().minCoeff().transpose();
  const Vec2 hi = material.colwise().maxCoeff().transpose();
  const Vec2 extent = (hi - lo).cwiseMax(1e-300);
  // About two triangles per bucket.
  const double area = extent.x() * extent.y();
  m_cell = std::sqrt(2.0 * area / std::max<double>(1.0, static_cast<double>(triangles.rows())));
  m_cell = std::max({m_cell, extent.x() * 1e-6, extent.y() * 1e-6});
  m_nx = std::max<Index>(1, static_cast<Index>(std::ceil(extent.x() / m_cell)));
  m_ny = std::max<Index>(1, static_cast<Index>(std::ceil(extent.y() / m_cell)));
  m_origin = lo;
  // Triangle boxes widened by a tolerance, so a point on an edge that lies on a bucket border
  // finds the triangle from either side.
  const double pad = 1e-9 * std::max(extent.x(), extent.y());
  std::vector<Index> count(static_cast<size_t>(m_nx * m_ny) + 1, 0);
  const auto for_each_bucket = [&](Index t, auto&& visit) {
    Vec2 tlo = material.row(triangles(t, 0)), thi = tlo;
    for (int k = 1; k < 3; ++k) {
      tlo = tlo.cwiseMin(Vec2(material.row(triangles(t, k))));
      thi = thi.cwiseMax(Vec2(material.row(triangles(t, k))));
    }
    const auto clampi = [](double x, Index n) {
      return std::clamp<Index>(static_cast<Index>(std::floor(x)), 0, n - 1);
    };
    const Index x0 = clampi((tlo.x() - pad - lo.x()) / m_cell, m_nx);
    const Index x1 = clampi((thi.x() + pad - lo.x()) / m_cell, m_nx);
    const Index y0 = clampi((tlo.y() - pad - lo.y()) / m_cell, m_ny);
    const Index y1 = clampi((thi.y() + pad - lo.y()) / m_cell, m_ny);
    for (Index y = y0; y <= y1; ++y)
      for (Index x = x0; x <= x1; ++x) visit(y * m_nx + x);
  };
  for (Index t = 0; t < triangles.rows(); ++t)
    for_each_bucket(t, [&](Index b) { ++count[static_cast<size_t>(b) + 1]; });
  std::partial_sum(count.begin(), count.end(), count.begin());
  m_bucket_start = count;
  m_bucket_items.resize(static_cast<size_t>(count.back()));
  std::vector<Index> fill(count.begin(), count.end() - 1);
  for (Index t = 0; t < triangles.rows(); ++t)
    for_each_bucket(t, [&](Index b) {
      m_bucket_items[static_cast<size_t>(fill[static_cast<size_t>(b)]++)] = t;
    });
}

std::array<double, 3> PointLocator::barycentric(Index t, const Vec2& p) const {
  const Vec2 a = m_material.row(m_triangles(t, 0)), b = m_material.row(m_triangles(t, 1)),
             c = m_material.row(m_triangles(t, 2));
  const double total = signed_area2(a, b, c);
  const double wa = signed_area2(p, b, c) / total;
  const double wb = signed_area2(a, p, c) / total;
  return {wa, wb, 1.0 - wa - wb};
}

Index PointLocator::bucket_of(const Vec2& p) const {
  // Clamped before the conversion: a point outside the box (a boundary point after rounding,
  // or far away) takes the nearest bucket.
  const auto cell = [&](double x, Index n) {
    return static_cast<Index>(std::clamp(std::floor(x / m_cell), 0.0, static_cast<double>(n - 1)));
  };
  return cell(p.y() - m_origin.y(), m_ny) * m_nx + cell(p.x() - m_origin.x(), m_nx);
}

Location PointLocator::best_of(const Index* begin, const Index* end, const Vec2& p) const {
  Location best;
  double best_min = -INFINITY;
  for (const Index* it = begin; it != end; ++it) {
    const auto w = barycentric(*it, p);
    const double smallest = std::min({w[0], w[1], w[2]});
    if (smallest > best_min) {  // strict: the lowest triangle index wins ties (deterministic)
      best_min = smallest;
      best = {*it, w};
    }
  }
  return best;
}

Location PointLocator::locate(const Vec2& p) const {
  if (!p.allFinite())
    throw std::invalid_argument("point location: material point (" + std::to_string(p.x()) + ", " +
                                std::to_string(p.y()) + ") is not finite");
  const Index b = bucket_of(p);
  const Index* items = m_bucket_items.data();
  Location found = best_of(items + m_bucket_start[static_cast<size_t>(b)],
                           items + m_bucket_start[static_cast<size_t>(b) + 1], p);
  if (found.triangle >= 0) return found;
  std::vector<Index> all(static_cast<size_t>(m_triangles.rows()));
  std::iota(all.begin(), all.end(), 0);
  return best_of(all.data(), all.data() + all.size(), p);
}

bool PointLocator::contains(const Vec2& p) const {
  if (!p.allFinite()) return false;
  const Index b = bucket_of(p);
  const Index* items = m_bucket_items.data();
  const Location found = best_of(items + m_bucket_start[static_cast<size_t>(b)],
                                 items + m_bucket_start[static_cast<size_t>(b) + 1], p);
  if (found.triangle < 0) return false;
  return std::min({found.barycentric[0], found.barycentric[1], found.barycentric[2]}) >= -1e-10;
}

}  // namespace weft::sim::remesh
