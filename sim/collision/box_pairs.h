#pragma once
// Every pair of overlapping boxes in one set, by a dense uniform grid: each box is entered in
// the cells it covers (a counting sort), and a pair is tested in the cells both cover and
// reported in one of them, the cell holding the low corner of the pair's index ranges' overlap.
// Closed boxes that overlap share a point whose cell both cover (the cell of a coordinate is
// monotone in it), so the answer is that of testing every pair (tests/sim/box_pairs_test.cpp),
// at a cost that grows with the boxes and their neighbours rather than with their square.
//
// The cells are cubes about as large as the median box, made larger when the grid would need
// more than cells_per_box cells a box. A box over more than max_cells_per_box cells (one far
// larger than the rest, as a cloth torn across the scene would give) is kept out of the grid and
// tested against every box, so that no box fills the grid. Boxes that are not finite or have lo
// above hi overlap nothing. Deterministic: the pairs come sorted.

#include <array>
#include <cstdint>
#include <vector>

#include "sim/collision/spatial_hash.h"
#include "sim/types.h"

namespace weft::sim {

class BoxPairs {
 public:
  // The pairs (a, b), a < b, of boxes that overlap (boxes_overlap), sorted, into `pairs`.
  void find(const std::vector<Aabb>& boxes, std::vector<std::array<Index, 2>>& pairs);

  // The grid has at most this many cells a box (its cells grow when the boxes' spread needs more).
  static constexpr std::size_t cells_per_box = 8;
  // A box over more cells than this is tested against every box instead.
  static constexpr std::int64_t max_cells_per_box = 64;

 private:
  // The grid over the usable boxes: its corner, cell edge and cells along each axis; false
  // when fewer than two boxes are usable.
  bool lay_out(const std::vector<Aabb>& boxes);
  void enter(const std::vector<Aabb>& boxes);
  void pair_in_cells(const std::vector<Aabb>& boxes, std::vector<std::array<Index, 2>>& pairs) const;
  void pair_oversized(const std::vector<Aabb>& boxes, std::vector<std::array<Index, 2>>& pairs) const;
  std::size_t cell_index(std::int32_t i, std::int32_t j, std::int32_t k) const;
  template <class Visit>
  void for_cells(const std::array<std::int32_t, 6>& range, Visit&& visit) const;

  Vec3 m_lo = Vec3::Zero();
  double m_edge = 1.0;
  std::array<std::int32_t, 3> m_dims{1, 1, 1};
  // Scratch kept between calls: each box's cell range, the cells' starts and their boxes.
  std::vector<std::array<std::int32_t, 6>> m_ranges;
  std::vector<std::int32_t> m_cell_start;
  std::vector<Index> m_entries;
  std::vector<double> m_sizes;
  std::vector<Index> m_oversized;  // ascending
};

}  // namespace weft::sim
