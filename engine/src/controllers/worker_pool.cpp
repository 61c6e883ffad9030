#include "controllers/worker_pool.h"

#include <algorithm>
#include <chrono>

namespace corsa::engine::detail {

namespace {

// How long the caller spins for the chunks workers have started before it sleeps: a few
// chunks' time (a chunk of 32 moves of 1,000 vehicles on Town04 takes 15-30 us).
constexpr std::chrono::microseconds kPoolSpinWait{100};
// How long a worker woken by prepare() spins for the run: longer than the serial work between
// the announcement and the run (about 60-100 us at 1,000 vehicles on Town04).
constexpr std::chrono::microseconds kWorkerSpinWait{300};

void pool_spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

}  // namespace

WorkerPool::WorkerPool(unsigned threads) : shares_(std::max(threads, 1u)) {
  for (unsigned w = 1; w < threads; ++w) {
    workers_.emplace_back([this, w] { serve(w); });
  }
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& worker : workers_) {
    worker.join();
  }
}

void WorkerPool::drain(unsigned worker) {
  std::exception_ptr error;
  // Its own share first, then what is left of the others'.
  for (size_t k = 0; k < shares_.size(); ++k) {
    PoolShare& share = shares_[(worker + k) % shares_.size()];
    while (true) {
      const size_t chunk = share.next.fetch_add(1, std::memory_order_relaxed);
      if (chunk >= share.end) {
        break;
      }
      const size_t begin = chunk * chunk_;
      try {
        (*work_)(begin, std::min(count_, begin + chunk_), worker);
      } catch (...) {
        if (!error) error = std::current_exception();
      }
    }
  }
  if (error) {
    std::lock_guard lock(mutex_);
    if (!error_) error_ = error;
  }
}

void WorkerPool::run(size_t count, size_t chunk,
                     const std::function<void(size_t, size_t, unsigned)>& work, After after) {
  {
    std::lock_guard lock(mutex_);
    work_ = &work;
    after_ = after;
    count_ = count;
    chunk_ = std::max<size_t>(chunk, 1);
    const size_t chunks = (count + chunk_ - 1) / chunk_;
    for (size_t w = 0; w < shares_.size(); ++w) {
      shares_[w].next.store(chunks * w / shares_.size(), std::memory_order_relaxed);
      shares_[w].end = chunks * (w + 1) / shares_.size();
    }
    error_ = nullptr;
    open_ = true;
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  drain(0);
  std::unique_lock lock(mutex_);
  open_ = false;  // a worker waking up from now on has missed this run
  if (active_.load(std::memory_order_relaxed) != 0) {
    // No worker joins any more: wait for those inside, first awake.
    lock.unlock();
    const auto until = std::chrono::steady_clock::now() + kPoolSpinWait;
    while (active_.load(std::memory_order_relaxed) != 0 &&
           std::chrono::steady_clock::now() < until) {
      pool_spin_pause();
    }
    lock.lock();
  }
  done_.wait(lock, [this] { return active_ == 0; });
  work_ = nullptr;
  if (error_) {
    std::rethrow_exception(error_);
  }
}

void WorkerPool::prepare() {
  if (workers_.empty()) {
    return;
  }
  {
    std::lock_guard lock(mutex_);
    ++prepared_;
  }
  start_.notify_all();
}

void WorkerPool::await_run(uint64_t seen, std::chrono::microseconds wait) const {
  const auto until = std::chrono::steady_clock::now() + wait;
  while (generation_.load(std::memory_order_acquire) == seen) {
    for (int k = 0; k < 32; ++k) {
      pool_spin_pause();
    }
    if (std::chrono::steady_clock::now() >= until) {
      return;
    }
  }
}

void WorkerPool::serve(unsigned worker) {
  uint64_t seen = 0;
  uint64_t prepared = 0;
  while (true) {
    std::unique_lock lock(mutex_);
    start_.wait(lock, [&] {
      return stop_ || generation_.load(std::memory_order_relaxed) != seen || prepared_ != prepared;
    });
    if (stop_) {
      return;
    }
    if (generation_.load(std::memory_order_relaxed) == seen) {
      // Woken ahead of a run: wait for it awake, then join it as if woken by it.
      prepared = prepared_;
      lock.unlock();
      await_run(seen, kWorkerSpinWait);
      continue;
    }
    prepared = prepared_;
    seen = generation_.load(std::memory_order_relaxed);
    const After after = after_;
    if (open_) {
      ++active_;
      lock.unlock();
      drain(worker);
      lock.lock();
      if (--active_ == 0) {
        done_.notify_one();
      }
    }
    if (after == After::kAwait) {
      // Another run follows soon (missed or not, this one): wait for it awake.
      lock.unlock();
      await_run(seen, kWorkerSpinWait);
    }
  }
}

}  // namespace corsa::engine::detail
