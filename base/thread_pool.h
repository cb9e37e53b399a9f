#pragma once
// One persistent, deterministic fork–join pool. Its threads start once, with the pool, and wait
// for work; run(tasks, task) runs task(0), …, task(tasks − 1), each once, spread over the pool's
// threads and the calling one, and returns when all have finished. Tasks are handed out in index
// order off a shared counter (so uneven tasks balance), and a task's result must depend on its
// index only: callers keep results per task and merge them in index order, and the output is the
// same bits for any number of threads.
//
// The pool is owned by its user (self-collision, the ray tracer), sized by that user's threads
// setting; there is no global pool. One run() at a time: a run() from inside a task (or from a
// second thread while one is going) runs its tasks on the calling thread, in order.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace weft::base {

// The machine's hardware threads (at least 1).
std::size_t hardware_threads();

// Threads to use for a `threads` setting: 0 means all hardware threads; otherwise `threads`
// itself (≥ 1). A negative setting is a bug here: settings are checked where they are read.
std::size_t thread_count(int threads);

// The first index of share k of n items split into `shares` contiguous shares whose sizes differ
// by at most one: share k is [share_begin(n, shares, k), share_begin(n, shares, k + 1)).
inline std::size_t share_begin(std::size_t n, std::size_t shares, std::size_t k) {
  return n * k / shares;
}

class ThreadPool {
 public:
  // thread_count(threads) threads in all, the caller's included (so threads − 1 are started).
  // Fewer when the system refuses to start more: size() says how many.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  // Threads that run tasks, the caller's included (≥ 1).
  std::size_t size() const { return m_workers.size() + 1; }

  // Runs task(k) for every k in [0, tasks) and returns when all finished. If tasks throw, no
  // further tasks are started, and the exception of the lowest failing k is rethrown here
  // (the same one for any number of threads, as tasks are started in index order).
  void run(std::size_t tasks, const std::function<void(std::size_t)>& task);

 private:
  void worker_loop();
  // Takes tasks off the counter until none are left (or one failed).
  void take_tasks();
  static void run_inline(std::size_t tasks, const std::function<void(std::size_t)>& task);

  std::vector<std::thread> m_workers;
  std::mutex m_mutex;
  std::condition_variable m_wake;     // a new run, or the end
  std::condition_variable m_settled;  // the last worker left a run
  std::uint64_t m_generation = 0;     // runs started
  std::size_t m_active = 0;           // workers not yet done with the current run
  bool m_stop = false;
  std::atomic<bool> m_busy{false};

  // The current run.
  const std::function<void(std::size_t)>* m_task = nullptr;
  std::size_t m_tasks = 0;
  std::atomic<std::size_t> m_next{0};
  std::atomic<bool> m_failed{false};
  std::size_t m_error_index = 0;  // guarded by m_mutex
  std::exception_ptr m_error;     // guarded by m_mutex
};

}  // namespace weft::base
