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
  if (!lay_out(boxes)) return;
  enter(boxes);
  pair_in_cells(boxes, pairs);
  pair_oversized(boxes, pairs);
  std::sort(pairs.begin(), pairs.end());
}

bool BoxPairs::lay_out(const std::vector<Aabb>& boxes) {
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  m_lo = -hi;
  m_sizes.clear();
  for (const Aabb& box : boxes) {
    if (!usable(box)) continue;
    m_lo = m_lo.cwiseMin(box.lo);
    hi = hi.cwiseMax(box.hi);
    m_sizes.push_back((box.hi - box.lo).maxCoeff());
  }
  if (m_sizes.size() < 2) return false;
  const Vec3 spread = hi - m_lo;
  m_edge = cell_edge(m_sizes, spread, static_cast<double>(cells_per_box * m_sizes.size()));
  for (int k = 0; k < 3; ++k) m_dims[k] = static_cast<std::int32_t>(std::floor(spread[k] / m_edge)) + 1;
  return true;
}

std::size_t BoxPairs::cell_index(std::int32_t i, std::int32_t j, std::int32_t k) const {
  return (static_cast<std::size_t>(k) * m_dims[1] + j) * m_dims[0] + i;
}

template <class Visit>
void BoxPairs::for_cells(const std::array<std::int32_t, 6>& range, Visit&& visit) const {
  for (std::int32_t k = range[2]; k <= range[5]; ++k)
    for (std::int32_t j = range[1]; j <= range[4]; ++j)
      for (std::int32_t i = range[0]; i <= range[3]; ++i) visit(cell_index(i, j, k));
}

// Each box's cell range (none for an unusable or oversized box), then a counting sort of the
// boxes into the cells: cell c holds m_entries[m_cell_start[c] .. m_cell_start[c + 1]),
// ascending.
void BoxPairs::enter(const std::vector<Aabb>& boxes) {
  const auto cell_of = [&](double coordinate, int k) {
    const double i = std::floor((coordinate - m_lo[k]) / m_edge);
    return static_cast<std::int32_t>(std::clamp(i, 0.0, static_cast<double>(m_dims[k] - 1)));
  };
  const std::size_t cell_count = static_cast<std::size_t>(m_dims[0]) * m_dims[1] * m_dims[2];
  m_ranges.resize(boxes.size());
  m_cell_start.assign(cell_count + 1, 0);
  m_oversized.clear();
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    auto& r = m_ranges[b];
    r = {0, 0, 0, -1, -1, -1};  // no cells
    if (!usable(boxes[b])) continue;
    std::array<std::int32_t, 6> range{};
    for (int k = 0; k < 3; ++k) {
      range[k] = cell_of(boxes[b].lo[k], k);
      range[k + 3] = cell_of(boxes[b].hi[k], k);
    }
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
  std::vector<std::int32_t>& next = m_cell_start;  // advanced while filling, then restored
  for (std::size_t b = 0; b < boxes.size(); ++b)
    for_cells(m_ranges[b], [&](std::size_t c) {
      m_entries[static_cast<std::size_t>(next[c]++)] = static_cast<Index>(b);
    });
  for (std::size_t c = cell_count; c > 0; --c) next[c] = next[c - 1];
  next[0] = 0;
}

// In each cell, the pairs whose cell ranges' overlap starts there: each pair in one cell.
void BoxPairs::pair_in_cells(const std::vector<Aabb>& boxes,
                             std::vector<std::array<Index, 2>>& pairs) const {
  for (std::int32_t k = 0; k < m_dims[2]; ++k)
    for (std::int32_t j = 0; j < m_dims[1]; ++j)
      for (std::int32_t i = 0; i < m_dims[0]; ++i) {
        const std::size_t c = cell_index(i, j, k);
        const auto end = static_cast<std::size_t>(m_cell_start[c + 1]);
        for (auto x = static_cast<std::size_t>(m_cell_start[c]); x < end; ++x) {
          const Index a = m_entries[x];
          const auto& ra = m_ranges[static_cast<std::size_t>(a)];
          for (std::size_t y = x + 1; y < end; ++y) {
            const Index b = m_entries[y];
            const auto& rb = m_ranges[static_cast<std::size_t>(b)];
            if (std::max(ra[0], rb[0]) == i && std::max(ra[1], rb[1]) == j &&
                std::max(ra[2], rb[2]) == k &&
                boxes_overlap(boxes[static_cast<std::size_t>(a)], boxes[static_cast<std::size_t>(b)]))
              pairs.push_back({a, b});
          }
        }
      }
}

// The oversized boxes against every box; a pair of two of them once.
void BoxPairs::pair_oversized(const std::vector<Aabb>& boxes,
                              std::vector<std::array<Index, 2>>& pairs) const {
  for (const Index a : m_oversized)
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      const auto other = static_cast<Index>(b);
      if (other == a || !usable(boxes[b]) || !boxes_overlap(boxes[static_cast<std::size_t>(a)], boxes[b]))
        continue;
      if (other < a && std::binary_search(m_oversized.begin(), m_oversized.end(), other)) continue;
      pairs.push_back({std::min(a, other), std::max(a, other)});
    }
}

}  // namespace weft::sim
