// The persistent fork–join pool of thread_pool.h.

#include "base/thread_pool.h"

#include <algorithm>
#include <limits>
#include <string>
#include <system_error>

#include "base/check.h"

namespace weft::base {

std::size_t hardware_threads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

std::size_t thread_count(int threads) {
  WEFT_CHECK(threads >= 0, "thread setting " + std::to_string(threads) + " was not checked");
  return threads > 0 ? static_cast<std::size_t>(threads) : hardware_threads();
}

ThreadPool::ThreadPool(int threads) {
  const std::size_t count = thread_count(threads);
  m_workers.reserve(count - 1);
  for (std::size_t t = 1; t < count; ++t) {
    try {
      m_workers.emplace_back(&ThreadPool::worker_loop, this);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the work is shared among those running
    }
  }
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_stop = true;
  }
  m_wake.notify_all();
  for (std::thread& t : m_workers) t.join();
}

void ThreadPool::run_inline(std::size_t tasks, const std::function<void(std::size_t)>& task) {
  for (std::size_t k = 0; k < tasks; ++k) task(k);
}

void ThreadPool::run(std::size_t tasks, const std::function<void(std::size_t)>& task) {
  bool idle = false;
  if (tasks <= 1 || m_workers.empty() || !m_busy.compare_exchange_strong(idle, true)) {
    run_inline(tasks, task);
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_task = &task;
    m_tasks = tasks;
    m_next = 0;
    m_failed = false;
    m_error = nullptr;
    m_error_index = std::numeric_limits<std::size_t>::max();
    m_active = m_workers.size();
    ++m_generation;
  }
  m_wake.notify_all();
  take_tasks();
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_settled.wait(lock, [this] { return m_active == 0; });
    m_task = nullptr;
    error = m_error;
    m_error = nullptr;
  }
  m_busy = false;
  if (error) std::rethrow_exception(error);
}

void ThreadPool::take_tasks() {
  for (;;) {
    if (m_failed.load(std::memory_order_relaxed)) return;
    const std::size_t k = m_next.fetch_add(1);
    if (k >= m_tasks) return;
    try {
      (*m_task)(k);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(m_mutex);
      if (k < m_error_index) {
        m_error_index = k;
        m_error = std::current_exception();
      }
      m_failed = true;
    }
  }
}

void ThreadPool::worker_loop() {
  std::uint64_t seen = 0;
  std::unique_lock<std::mutex> lock(m_mutex);
  for (;;) {
    m_wake.wait(lock, [&] { return m_stop || m_generation != seen; });
    if (m_stop) return;
    seen = m_generation;
    lock.unlock();
    take_tasks();
    lock.lock();
    if (--m_active == 0) m_settled.notify_one();
  }
}

}  // namespace weft::base
