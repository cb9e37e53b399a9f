#pragma once
// Broad phase for self-collision: a uniform grid of cubic cells, hashed by
// integer cell coordinates, over axis-aligned boxes. Deterministic: a query returns the ids of
// every box that overlaps the query box, sorted ascending and each once; the set does not depend
// on the boxes' order. No global state; one hash per set of boxes.
//
// Completeness: two closed boxes that overlap share a point, and that point's cell (floor of
// coordinate / cell size, monotone in floating point) is covered by both boxes, so every
// overlapping box is found. Candidates are then filtered by the exact box-overlap test, so the
// answer equals brute force over all boxes (tests/sim/self_intersection_test.cpp).

#include <cstdint>
#include <vector>

#include "sim/types.h"

namespace weft::sim {

// Closed axis-aligned box [lo, hi], metres.
struct Aabb {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
};

Aabb bounding_box(const Vec3& a, const Vec3& b);
Aabb bounding_box(const Vec3& a, const Vec3& b, const Vec3& c);
// Closed intervals: touching boxes overlap.
inline bool boxes_overlap(const Aabb& a, const Aabb& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}
// The box grown by by_m on every side.
inline Aabb inflated(Aabb box, double by_m) {
  box.lo.array() -= by_m;
  box.hi.array() += by_m;
  return box;
}

class SpatialHash {
 public:
  // Builds the hash over `boxes`; a box's id is its index. cell_size_m: edge of a cubic cell,
  // metres — about the size of one box (e.g. the mean triangle extent) works well. Throws
  // std::invalid_argument unless cell_size_m is finite > 0 and every box is finite with lo ≤ hi
  // (naming the box). A box covering more than max_cells_per_box cells is kept on a list every
  // query scans.
  SpatialHash(double cell_size_m, std::vector<Aabb> boxes);

  // Ids of the boxes overlapping `box`, sorted ascending, without repeats.
  std::vector<Index> query(const Aabb& box) const;
  // The same into `ids` (cleared first), reusing its storage across calls.
  void query(const Aabb& box, std::vector<Index>& ids) const;

  double cell_size_m() const { return m_cell_size_m; }
  std::size_t box_count() const { return m_boxes.size(); }

  static constexpr double max_cells_per_box = 512.0;

 private:
  struct CellRange {
    std::int64_t lo[3], hi[3];
    bool bounded;  // false: too many cells (or too far out) to enumerate
  };
  CellRange cell_range(const Aabb& box) const;
  std::size_t bucket(std::int64_t i, std::int64_t j, std::int64_t k) const;

  double m_cell_size_m;
  std::vector<Aabb> m_boxes;
  // Teschner et al. 2003's table: cell → bucket by hashing; bucket b holds the boxes
  // m_entries[m_bucket_start[b] .. m_bucket_start[b+1]) (those of every cell hashed to b).
  std::size_t m_bucket_mask = 0;
  std::vector<Index> m_bucket_start;
  std::vector<Index> m_entries;
  std::vector<Index> m_oversized;  // boxes covering too many cells, scanned by every query
};

}  // namespace weft::sim
