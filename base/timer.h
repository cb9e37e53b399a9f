#pragma once
// Wall time on the monotonic clock: the one timer of sim, render, app and the benchmarks.

#include <chrono>

namespace weft::base {

// Starts at construction; seconds() is the time since then (or since the last restart()).
class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  Stopwatch() : m_start(Clock::now()) {}
  void restart() { m_start = Clock::now(); }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - m_start).count(); }
  double milliseconds() const { return 1e3 * seconds(); }

 private:
  Clock::time_point m_start;
};

}  // namespace weft::base
