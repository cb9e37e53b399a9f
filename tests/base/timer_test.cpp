// The Stopwatch reads a monotonic clock: never backwards, and it sees a sleep.

#include "base/timer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace weft::base {
namespace {

TEST(Stopwatch, IsMonotone) {
  const Stopwatch watch;
  double last = 0.0;
  for (int k = 0; k < 10000; ++k) {
    const double now = watch.seconds();
    ASSERT_GE(now, last);
    last = now;
  }
  static_assert(Stopwatch::Clock::is_steady, "the timer's clock must be monotonic");
}

TEST(Stopwatch, MeasuresASleepAndRestarts) {
  Stopwatch watch;
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_GE(watch.seconds(), 0.020);
  EXPECT_NEAR(watch.milliseconds(), 1e3 * watch.seconds(), 5.0);
  watch.restart();
  EXPECT_LT(watch.seconds(), 0.020);
}

}  // namespace
}  // namespace weft::base
