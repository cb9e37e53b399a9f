// Fork–join over contiguous shares; see parallel_shares.h.

#include "sim/parallel_shares.h"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace weft::sim {

void run_in_shares(std::size_t shares, const std::function<void(std::size_t)>& task) {
  if (shares <= 1) {
    if (shares == 1) task(0);
    return;
  }
  std::vector<std::exception_ptr> errors(shares);
  const auto guarded = [&](std::size_t k) {
    try {
      task(k);
    } catch (...) {
      errors[k] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(shares - 1);
  for (std::size_t k = 1; k < shares; ++k) threads.emplace_back(guarded, k);
  guarded(0);
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

std::size_t thread_count(int threads) {
  if (threads > 0) return static_cast<std::size_t>(threads);
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace weft::sim
