#include "corsa/sweep/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace corsa::sweep {

size_t default_jobs() { return std::max<size_t>(1, std::thread::hardware_concurrency()); }

void parallel_for(size_t count, size_t jobs, const std::function<void(size_t)>& body) {
  const size_t threads = std::min(count, jobs == 0 ? default_jobs() : jobs);
  if (threads <= 1) {
    for (size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    while (!stop.load(std::memory_order_relaxed)) {
      const size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= count) return;
      try {
        body(i);
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        stop.store(true, std::memory_order_relaxed);
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads);
  try {
    for (size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
  } catch (...) {
    // Could not start another thread: the ones running finish the work (or stop on failure).
    if (pool.empty()) throw;
  }
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace corsa::sweep
