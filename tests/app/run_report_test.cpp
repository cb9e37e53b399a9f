// The pieces of weft run --report: frames spread evenly over a run (its charts' ticks and
// points: tests/chart/chart_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "app/report/run_report.h"

namespace {

using weft::app::evenly_spaced_frames;

TEST(EvenlySpacedFrames, FirstAndLastIncludedAndGapsDifferByAtMostOne) {
  for (const int frames : {12, 13, 50, 72, 97, 1000}) {
    SCOPED_TRACE(frames);
    const std::vector<int> f = evenly_spaced_frames(frames, 12);
    ASSERT_EQ(f.size(), 12u);
    EXPECT_EQ(f.front(), 1);
    EXPECT_EQ(f.back(), frames);
    int lo = frames, hi = 0;
    for (std::size_t k = 1; k < f.size(); ++k) {
      lo = std::min(lo, f[k] - f[k - 1]);
      hi = std::max(hi, f[k] - f[k - 1]);
    }
    EXPECT_GE(lo, 1);
    EXPECT_LE(hi - lo, 1);
  }
  EXPECT_EQ(evenly_spaced_frames(5, 12), (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(evenly_spaced_frames(5, 1), (std::vector<int>{5}));
}

}  // namespace
