// The thread pool: every task runs exactly once for any thread count; contiguous shares cover
// the items exactly; results merged in task order are the same bits for any thread count; the
// lowest failing task's exception comes back; nested runs and reuse work.

#include "base/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/check.h"

namespace weft::base {
namespace {

TEST(ThreadCount, ZeroMeansAllHardwareThreads) {
  EXPECT_EQ(thread_count(0), hardware_threads());
  EXPECT_GE(hardware_threads(), 1u);
  EXPECT_EQ(thread_count(3), 3u);
  EXPECT_THROW((void)thread_count(-1), InternalError);  // settings are checked where read
}

TEST(ShareBegin, SharesCoverTheItemsContiguously) {
  for (std::size_t n : {0u, 1u, 5u, 64u, 1000u, 1001u}) {
    for (std::size_t shares = 1; shares <= 9; ++shares) {
      EXPECT_EQ(share_begin(n, shares, 0), 0u);
      EXPECT_EQ(share_begin(n, shares, shares), n);
      for (std::size_t k = 0; k < shares; ++k) {
        const std::size_t size = share_begin(n, shares, k + 1) - share_begin(n, shares, k);
        EXPECT_LE(size, n / shares + 1) << n << " items, " << shares << " shares";
        EXPECT_GE(size, n / shares) << n << " items, " << shares << " shares";
      }
    }
  }
}

TEST(ThreadPool, RunsEveryTaskExactlyOnce) {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    EXPECT_GE(pool.size(), 1u);
    EXPECT_LE(pool.size(), static_cast<std::size_t>(threads));
    for (std::size_t tasks : {0u, 1u, 2u, 7u, 1000u}) {
      std::vector<std::atomic<int>> runs(tasks);
      pool.run(tasks, [&](std::size_t k) { ++runs[k]; });
      for (std::size_t k = 0; k < tasks; ++k)
        ASSERT_EQ(runs[k].load(), 1) << "task " << k << " of " << tasks << ", " << threads
                                     << " threads";
    }
  }
}

// A floating-point sum over contiguous shares merged in share order: the same bits for any
// number of threads (the shares are fixed; only who runs them changes).
double share_sum(ThreadPool& pool, const std::vector<double>& values, std::size_t shares) {
  std::vector<double> partial(shares, 0.0);
  pool.run(shares, [&](std::size_t k) {
    const std::size_t end = share_begin(values.size(), shares, k + 1);
    for (std::size_t i = share_begin(values.size(), shares, k); i < end; ++i)
      partial[k] += values[i];
  });
  double sum = 0.0;
  for (double p : partial) sum += p;
  return sum;
}

TEST(ThreadPool, ResultsMergedInShareOrderAreTheSameBitsForAnyThreadCount) {
  std::vector<double> values(100000);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = std::sin(0.37 * static_cast<double>(i)) * std::pow(10.0, static_cast<double>(i % 17) - 8.0);
  ThreadPool one(1);
  const double reference = share_sum(one, values, 16);
  for (int threads : {2, 3, 4, 7}) {
    ThreadPool pool(threads);
    for (int repeat = 0; repeat < 5; ++repeat)
      EXPECT_EQ(share_sum(pool, values, 16), reference) << threads << " threads";
  }
}

TEST(ThreadPool, RethrowsTheLowestFailingTaskAndStaysUsable) {
  ThreadPool pool(4);
  for (int repeat = 0; repeat < 20; ++repeat) {
    try {
      pool.run(200, [](std::size_t k) {
        if (k == 37 || k == 38 || k == 150) throw std::runtime_error(std::to_string(k));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "37");
    }
  }
  std::atomic<int> count{0};
  pool.run(100, [&](std::size_t) { ++count; });
  EXPECT_EQ(count.load(), 100);
}

TEST(ThreadPool, NestedRunRunsOnTheCallingThread) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> runs(6 * 5);
  pool.run(6, [&](std::size_t i) { pool.run(5, [&](std::size_t j) { ++runs[5 * i + j]; }); });
  for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
}

}  // namespace
}  // namespace weft::base
