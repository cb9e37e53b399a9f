#pragma once
// Fork–join over a few threads for work split into contiguous shares: share k of a loop is
// run as task(k) for k in [0, shares), share 0 on the calling thread and each other one on a
// thread of its own, and the call returns once all have finished. Callers keep results per
// share and join them in share order, so what they compute does not depend on the number of
// threads.

#include <cstddef>
#include <functional>

namespace weft::sim {

// Runs task(0), …, task(shares − 1) at once (shares ≥ 1; with 1, on this thread only). An
// exception from a task is rethrown here — the one of the lowest share — after all finished.
void run_in_shares(std::size_t shares, const std::function<void(std::size_t)>& task);

// The first index of share k of n items split into `shares` contiguous shares of sizes that
// differ by at most one: share k is [share_begin(n, shares, k), share_begin(n, shares, k + 1)).
inline std::size_t share_begin(std::size_t n, std::size_t shares, std::size_t k) {
  return n * k / shares;
}

// Threads to use for `threads` (0: all hardware threads, at least 1).
std::size_t thread_count(int threads);

}  // namespace weft::sim
