// Overlapping box pairs on a uniform grid; see box_pairs.h.

#include "sim/collision/box_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::sim {
namespace {

bool usable(const Aabb& box) {
  return box.lo.allFinite() && box.hi.allFinite() && (box.lo.array() <= box.hi.array()).all();
}

// The cell edge: the median of the boxes' largest extents, or (all of them points) the spread
// over the cube root of their number; grown until the grid has at most max_cells cells.
double cell_edge(std::vector<double>& sizes, const Vec3& spread, double max_cells) {
  double edge = 0.0;
  if (!sizes.empty()) {
    const auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
    std::nth_element(sizes.begin(), middle, sizes.end());
    edge = *middle;
  }
  if (!(edge > 0.0)) edge = spread.maxCoeff() / std::cbrt(static_cast<double>(sizes.size()) + 1.0);
  if (!(edge > 0.0)) edge = 1.0;
  const auto cells = [&](double e) {
    return (std::floor(spread.x() / e) + 1.0) * (std::floor(spread.y() / e) + 1.0) *
           (std::floor(spread.z() / e) + 1.0);
  };
  while (cells(edge) > max_cells) edge *= 1.25;
  return edge;
}

}  // namespace

void BoxPairs::find(const std::vector<Aabb>& boxes, std::vector<std::array<Index, 2>>& pairs) {
  pairs.clear();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  m_sizes.clear();
  for (const Aabb& box : boxes) {
    if (!usable(box)) continue;
    lo = lo.cwiseMin(box.lo);
    hi = hi.cwiseMax(box.hi);
    m_sizes.push_back((box.hi - box.lo).maxCoeff());
  }
  if (m_sizes.size() < 2) return;
  const Vec3 spread = hi - lo;
  const double max_cells = static_cast<double>(cells_per_box * m_sizes.size());
  const double edge = cell_edge(m_sizes, spread, max_cells);
  std::array<std::int32_t, 3> dims{};
  for (int k = 0; k < 3; ++k) dims[k] = static_cast<std::int32_t>(std::floor(spread[k] / edge)) + 1;
  const auto cell_of = [&](double coordinate, int k) {
    const double i = std::floor((coordinate - lo[k]) / edge);
    return static_cast<std::int32_t>(std::clamp(i, 0.0, static_cast<double>(dims[k] - 1)));
  };
  // Each box's cell range (empty for an unusable box), then a counting sort into the cells.
  const std::size_t cell_count = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  const auto cell_index = [&](std::int32_t i, std::int32_t j, std::int32_t k) {
    return (static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i;
  };
  m_ranges.resize(boxes.size());
  m_cell_start.assign(cell_count + 1, 0);
  const auto for_cells = [&](const std::array<std::int32_t, 6>& r, auto&& visit) {
    for (std::int32_t k = r[2]; k <= r[5]; ++k)
      for (std::int32_t j = r[1]; j <= r[4]; ++j)
        for (std::int32_t i = r[0]; i <= r[3]; ++i) visit(cell_index(i, j, k));
  };
  m_oversized.clear();
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    auto& r = m_ranges[b];
    r = {0, 0, 0, -1, -1, -1};  // no cells
    if (!usable(boxes[b])) continue;
    std::array<std::int32_t, 6> range{};
    for (int k = 0; k < 3; ++k) range[k] = cell_of(boxes[b].lo[k], k), range[k + 3] = cell_of(boxes[b].hi[k], k);
    std::int64_t cells = 1;
    for (int k = 0; k < 3; ++k) cells *= range[k + 3] - range[k] + 1;
    if (cells > max_cells_per_box) {
      m_oversized.push_back(static_cast<Index>(b));
      continue;
    }
    r = range;
    for_cells(r, [&](std::size_t c) { ++m_cell_start[c + 1]; });
  }
  for (std::size_t c = 0; c < cell_count; ++c) m_cell_start[c + 1] += m_cell_start[c];
  m_entries.resize(static_cast<std::size_t>(m_cell_start[cell_count]));
  std::vector<std::int32_t>& fill = m_cell_start;  // advanced while filling, then restored
  for (std::size_t b = 0; b < boxes.size(); ++b)
    for_cells(m_ranges[b], [&](std::size_t c) { m_entries[static_cast<std::size_t>(fill[c]++)] = static_cast<Index>(b); });
  for (std::size_t c = cell_count; c > 0; --c) fill[c] = fill[c - 1];
  fill[0] = 0;
  // In each cell, the pairs whose ranges' overlap starts there.
  for (std::int32_t k = 0; k < dims[2]; ++k)
    for (std::int32_t j = 0; j < dims[1]; ++j)
      for (std::int32_t i = 0; i < dims[0]; ++i) {
        const std::size_t c = cell_index(i, j, k);
        const auto first = static_cast<std::size_t>(m_cell_start[c]);
        const auto end = static_cast<std::size_t>(m_cell_start[c + 1]);
        for (std::size_t x = first; x < end; ++x) {
          const Index a = m_entries[x];
          const auto& ra = m_ranges[static_cast<std::size_t>(a)];
          for (std::size_t y = x + 1; y < end; ++y) {
            const Index b = m_entries[y];
            const auto& rb = m_ranges[static_cast<std::size_t>(b)];
            if (std::max(ra[0], rb[0]) != i || std::max(ra[1], rb[1]) != j ||
                std::max(ra[2], rb[2]) != k)
              continue;
            if (boxes_overlap(boxes[static_cast<std::size_t>(a)], boxes[static_cast<std::size_t>(b)]))
              pairs.push_back({a, b});
          }
        }
      }
  // The oversized boxes against every box; a pair of two of them once.
  for (const Index a : m_oversized)
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      const auto other = static_cast<Index>(b);
      if (other == a || !usable(boxes[b]) || !boxes_overlap(boxes[static_cast<std::size_t>(a)], boxes[b]))
        continue;
      if (std::binary_search(m_oversized.begin(), m_oversized.end(), other) && other < a) continue;
      pairs.push_back({std::min(a, other), std::max(a, other)});
    }
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace weft::sim
