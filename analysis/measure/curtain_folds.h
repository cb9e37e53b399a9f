#pragma once
// Folds of a hanging curtain, to set the tension-field shape beside the simulated one. A
// cloth hanging from supports at its top corners forms swags stacked one below the other
// (seed 001's wrinkle lines); down the middle of the curtain they show as bulges that alternate
// out of the supports' plane, one way then the other. The count is the number of those
// alternating extremes of the centre column's out-of-plane offset, found by a zigzag with a
// hysteresis of min_prominence_m: an extreme counts once the offset has come back from it by at
// least that much, and the top and bottom of the column count when the offset moves away from
// them by that much. A tension-field shape with n wrinkles has n + 1 lines (0 … n) and so
// gives n + 1; a flat curtain gives 0.

#include <vector>

#include "sim/grid.h"
#include "sim/types.h"

namespace weft::analysis {

// The alternating extremes of a sequence (zigzag with hysteresis min_prominence, > 0).
int count_alternating_extremes(const std::vector<double>& values, double min_prominence);

struct CurtainFolds {
  int folds = 0;                    // alternating extremes down the centre column
  std::vector<double> offsets_m;    // the centre column's out-of-plane offsets, top to bottom
  double min_prominence_m = 0.0;    // the hysteresis used
};

// The curtain hangs along weft (v = 0 at the top) with warp across; the supports' plane holds
// the top edge's corners and the weft axis, its normal is warp × weft. The centre column is
// the grid column nearest the middle of the warp extent. The hysteresis is the larger of
// prominence_fraction of the offsets' range and min_prominence_m. Throws std::invalid_argument
// for a grid narrower than 2 vertices or x of the wrong size.
CurtainFolds count_curtain_folds(const sim::ClothMesh& mesh, const sim::Matrix3X& x,
                                 double prominence_fraction = 0.1, double min_prominence_m = 2e-3);

}  // namespace weft::analysis
