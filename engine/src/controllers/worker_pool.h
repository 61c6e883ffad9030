#pragma once

// A few threads kept for the moves of a step (controllers/controllers.h, EntityMover): a step's
// entities are cut into as many contiguous runs as there are threads, the calling thread takes
// the first and waits for the others. Which thread moves which entity does not change a result
// (each move reads only its own entity and the picture taken before the moves), so the cut is
// simply even.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace corsa::engine::detail {

class WorkerPool {
 public:
  /// `threads` in all, the caller's included (at least 1).
  explicit WorkerPool(unsigned threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }

  /// Calls work(begin, end, worker) for the runs of [0, count), worker 0 on the calling
  /// thread, and returns when all are done. An exception of any run is rethrown here.
  void run(size_t count, const std::function<void(size_t, size_t, unsigned)>& work);

 private:
  void serve(unsigned worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_;
  const std::function<void(size_t, size_t, unsigned)>* work_ = nullptr;
  size_t count_ = 0;
  uint64_t generation_ = 0;
  unsigned pending_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace corsa::engine::detail
