// app/fit/chamfer_3d.h: the 3D Chamfer distance on point sets whose distances are known.
#include "app/fit/chamfer_3d.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace weft::app {
namespace {

// An n × n grid of points with spacing h in the plane z = z0.
Points grid(int n, double h, double z0) {
  Points p(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) p.row(i * n + j) << i * h, j * h, z0;
  return p;
}

TEST(Chamfer3d, ParallelGridsAreTheirOffsetApart) {
  const Chamfer3d c = chamfer_3d(grid(10, 0.01, 0.0), grid(10, 0.01, 0.003));
  EXPECT_NEAR(c.a_to_b_m, 0.003, 1e-15);
  EXPECT_NEAR(c.b_to_a_m, 0.003, 1e-15);
  EXPECT_NEAR(c.symmetric_m, 0.003, 1e-15);
}

TEST(Chamfer3d, ASubsetIsAtZeroOneWayOnly) {
  // Every other row of the grid: the subset lies on the grid (0), the grid's other rows are a
  // spacing h from it: half the points at h, so a mean of h/2 that way.
  const Points all = grid(4, 0.02, 0.0);
  Points half(8, 3);
  for (int k = 0, r = 0; r < 16; ++r)
    if ((r / 4) % 2 == 0) half.row(k++) = all.row(r);
  const Chamfer3d c = chamfer_3d(half, all);
  EXPECT_EQ(c.a_to_b_m, 0.0);
  EXPECT_NEAR(c.b_to_a_m, 0.01, 1e-15);
  EXPECT_NEAR(c.symmetric_m, 0.005, 1e-15);
  EXPECT_THROW(chamfer_3d(Points(0, 3), all), std::invalid_argument);
}

}  // namespace
}  // namespace weft::app
