#include "controllers/worker_pool.h"

namespace corsa::engine::detail {
namespace {

// The run of worker `w` of `n` over [0, count).
void bounds(size_t count, unsigned n, unsigned w, size_t& begin, size_t& end) {
  begin = count * w / n;
  end = count * (w + 1) / n;
}

}  // namespace

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

void WorkerPool::run(size_t count, const std::function<void(size_t, size_t, unsigned)>& work) {
  const unsigned n = threads();
  {
    std::lock_guard lock(mutex_);
    work_ = &work;
    count_ = count;
    pending_ = n - 1;
    error_ = nullptr;
    ++generation_;
  }
  start_.notify_all();
  std::exception_ptr mine;
  try {
    size_t begin = 0, end = 0;
    bounds(count, n, 0, begin, end);
    work(begin, end, 0);
  } catch (...) {
    mine = std::current_exception();
  }
  std::unique_lock lock(mutex_);
  done_.wait(lock, [this] { return pending_ == 0; });
  work_ = nullptr;
  if (mine) {
    std::rethrow_exception(mine);
  }
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
    const auto* work = work_;
    const size_t count = count_;
    lock.unlock();
    std::exception_ptr error;
    try {
      size_t begin = 0, end = 0;
      bounds(count, threads(), worker, begin, end);
      (*work)(begin, end, worker);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !error_) {
      error_ = error;
    }
    if (--pending_ == 0) {
      done_.notify_one();
    }
  }
}

}  // namespace corsa::engine::detail
