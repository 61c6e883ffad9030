#include "controllers/worker_pool.h"

#include <algorithm>

namespace corsa::engine::detail {

WorkerPool::WorkerPool(unsigned threads) {
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
  while (true) {
    const size_t begin = next_.fetch_add(chunk_, std::memory_order_relaxed);
    if (begin >= count_) {
      break;
    }
    try {
      (*work_)(begin, std::min(count_, begin + chunk_), worker);
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (error) {
    std::lock_guard lock(mutex_);
    if (!error_) error_ = error;
  }
}

void WorkerPool::run(size_t count, size_t chunk,
                     const std::function<void(size_t, size_t, unsigned)>& work) {
  {
    std::lock_guard lock(mutex_);
    work_ = &work;
    count_ = count;
    chunk_ = std::max<size_t>(chunk, 1);
    next_.store(0, std::memory_order_relaxed);
    error_ = nullptr;
    open_ = true;
    ++generation_;
  }
  start_.notify_all();
  drain(0);
  std::unique_lock lock(mutex_);
  open_ = false;  // a worker waking up from now on has missed this run
  done_.wait(lock, [this] { return active_ == 0; });
  work_ = nullptr;
  if (error_) {
    std::rethrow_exception(error_);
  }
}

void WorkerPool::serve(unsigned worker) {
  uint64_t seen = 0;
  while (true) {
    std::unique_lock lock(mutex_);
    start_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) {
      return;
    }
    seen = generation_;
    if (!open_) {
      continue;
    }
    ++active_;
    lock.unlock();
    drain(worker);
    lock.lock();
    if (--active_ == 0) {
      done_.notify_one();
    }
  }
}

}  // namespace corsa::engine::detail
