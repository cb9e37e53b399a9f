#pragma once
// The dynamic state of a cloth: positions and velocities at a time.

#include "sim/types.h"

namespace weft::sim {

struct State {
  Matrix3X x;         // #V×3 positions, m
  Matrix3X v;         // #V×3 velocities, m/s
  double time_s = 0;  // simulated time
};

}  // namespace weft::sim
