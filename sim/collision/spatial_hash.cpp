#include "sim/collision/spatial_hash.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace weft::sim {

Aabb bounding_box(const Vec3& a, const Vec3& b) {
  return {a.cwiseMin(b), a.cwiseMax(b)};
}

Aabb bounding_box(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

SpatialHash::SpatialHash(double cell_size_m, std::vector<Aabb> boxes)
    : m_cell_size_m(cell_size_m), m_boxes(std::move(boxes)) {
  if (!(std::isfinite(cell_size_m) && cell_size_m > 0.0))
    throw std::invalid_argument("spatial hash: cell size must be finite and > 0 m, got " +
                                std::to_string(cell_size_m));
  std::vector<CellRange> ranges;
  ranges.reserve(m_boxes.size());
  std::size_t cell_entries = 0;
  for (std::size_t b = 0; b < m_boxes.size(); ++b) {
    const Aabb& box = m_boxes[b];
    if (!(box.lo.allFinite() && box.hi.allFinite()))
      throw std::invalid_argument("spatial hash: box " + std::to_string(b) +
                                  " has a non-finite coordinate");
    if (!(box.lo.array() <= box.hi.array()).all())
      throw std::invalid_argument("spatial hash: box " + std::to_string(b) + " has lo > hi");
    ranges.push_back(cell_range(box));
    const CellRange& r = ranges.back();
    if (r.bounded)
      cell_entries += static_cast<std::size_t>((r.hi[0] - r.lo[0] + 1) * (r.hi[1] - r.lo[1] + 1) *
                                               (r.hi[2] - r.lo[2] + 1));
    else
      m_oversized.push_back(static_cast<Index>(b));
  }
  // About two buckets per cell entry, a power of two; then a counting sort by bucket.
  std::size_t buckets = 1;
  while (buckets < 2 * cell_entries) buckets *= 2;
  m_bucket_mask = buckets - 1;
  m_bucket_start.assign(buckets + 1, 0);
  const auto for_each_cell = [&](auto&& visit) {
    for (std::size_t b = 0; b < ranges.size(); ++b) {
      const CellRange& r = ranges[b];
      if (!r.bounded) continue;
      for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i)
        for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
          for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k) visit(bucket(i, j, k), b);
    }
  };
  for_each_cell([&](std::size_t h, std::size_t) { ++m_bucket_start[h + 1]; });
  for (std::size_t h = 0; h < buckets; ++h) m_bucket_start[h + 1] += m_bucket_start[h];
  m_entries.resize(cell_entries);
  std::vector<Index> fill(m_bucket_start.begin(), m_bucket_start.end() - 1);
  for_each_cell([&](std::size_t h, std::size_t b) {
    m_entries[static_cast<std::size_t>(fill[h]++)] = static_cast<Index>(b);
  });
}

std::size_t SpatialHash::bucket(std::int64_t i, std::int64_t j, std::int64_t k) const {
  // Large primes as in Teschner et al. 2003, "Optimized spatial hashing for collision detection
  // of deformable objects"; two cells sharing a bucket only cost time (boxes are re-checked).
  const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
  const std::uint64_t h = u(i) * 73856093ULL ^ u(j) * 19349663ULL ^ u(k) * 83492791ULL;
  return static_cast<std::size_t>(h ^ (h >> 29)) & m_bucket_mask;
}

SpatialHash::CellRange SpatialHash::cell_range(const Aabb& box) const {
  const Eigen::Array3d lo = (box.lo / m_cell_size_m).array().floor();
  const Eigen::Array3d hi = (box.hi / m_cell_size_m).array().floor();
  constexpr double far_cells = 1e15;  // beyond this, cell coordinates would not fit exactly
  const double cells = (hi - lo + 1.0).prod();
  CellRange range{};
  range.bounded = lo.abs().maxCoeff() < far_cells && hi.abs().maxCoeff() < far_cells &&
                  cells <= max_cells_per_box;
  if (range.bounded)
    for (int a = 0; a < 3; ++a) {
      range.lo[a] = static_cast<std::int64_t>(lo[a]);
      range.hi[a] = static_cast<std::int64_t>(hi[a]);
    }
  return range;
}

std::vector<Index> SpatialHash::query(const Aabb& box) const {
  std::vector<Index> ids;
  query(box, ids);
  return ids;
}

void SpatialHash::query(const Aabb& box, std::vector<Index>& ids) const {
  ids.clear();
  // Gather candidate boxes from the buckets of the query's cells, then keep those overlapping.
  const CellRange r = box.lo.allFinite() && box.hi.allFinite() ? cell_range(box) : CellRange{};
  if (r.bounded) {
    for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i)
      for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
        for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k) {
          const std::size_t h = bucket(i, j, k);
          ids.insert(ids.end(), m_entries.begin() + m_bucket_start[h],
                     m_entries.begin() + m_bucket_start[h + 1]);
        }
    ids.insert(ids.end(), m_oversized.begin(), m_oversized.end());
  } else {
    // A query box too large to enumerate its cells: test every box.
    ids.resize(m_boxes.size());
    for (std::size_t b = 0; b < m_boxes.size(); ++b) ids[b] = static_cast<Index>(b);
  }
  // Filter first: most candidates do not overlap, and sorting the rest is then cheap.
  ids.erase(std::remove_if(ids.begin(), ids.end(),
                           [&](Index b) {
                             return !boxes_overlap(m_boxes[static_cast<std::size_t>(b)], box);
                           }),
            ids.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

}  // namespace weft::sim
