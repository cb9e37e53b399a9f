#pragma once
// Every pair of overlapping boxes in one set, by a dense uniform grid: each box is entered in
// the cells it covers (a counting sort), and a pair is tested in the cells both cover and
// reported in one of them, the cell holding the low corner of the pair's index ranges' overlap.
// Closed boxes that overlap share a point whose cell both cover (the cell of a coordinate is
// monotone in it), so the answer is that of testing every pair (tests/sim/box_pairs_test.cpp),
// at a cost that grows with the boxes and their neighbours rather than with their square.
//
// The cells are cubes about as large as the median box, made larger when that would need more
// than a few cells a box. Boxes that are not finite overlap nothing. Deterministic: the pairs
// come sorted.

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

  // At most this many cells a box in the grid (the cells grow when the boxes' spread needs more).
  static constexpr std::size_t cells_per_box = 8;

 private:
  // Scratch kept between calls: each box's cell range, the cells' starts and their boxes.
  std::vector<std::array<std::int32_t, 6>> m_ranges;
  std::vector<std::int32_t> m_cell_start;
  std::vector<Index> m_entries;
  std::vector<double> m_sizes;
};

}  // namespace weft::sim
