#pragma once

// A few threads kept for the moves of a step (controllers/controllers.h, EntityMover): a step's
// entities are cut into chunks that the calling thread and the workers take one after the other
// from a shared counter. Which thread moves which entity does not change a result (each move
// reads only its own entity and the picture taken before the moves), so the chunks go to
// whoever is free. The calling thread never waits for a worker to wake up: on a machine whose
// cores are busy with other work a worker may get its core only milliseconds later, and the
// caller then moves every chunk itself; it waits only for chunks a worker has started.
//
// Each thread first takes the chunks of its own share, the same part of the items every run
// (thread w: the w-th of `threads` equal runs of chunks), and then those left in the others'
// shares. A step's entities are moved in the same order for many steps, so each entity is
// moved on the same core step after step and its state stays in that core's cache; chunks
// taken from one shared counter went to whichever thread came first, and half of the moved
// state then crossed between the cores' caches every step.
//
// The caller waits for the chunks a worker has started by spinning for a short while before it
// sleeps: a chunk takes some tens of microseconds, and on a virtual machine a core that went to
// sleep wakes up only about as late again.
//
// A worker woken through the kernel when a run starts joins it late (on a virtual machine about
// as late as the caller's share of a step's moves takes), and the hand-over costs both threads
// CPU time in the kernel (docs/performance/two-threads.md gives the figures). So
// the caller announces a run (prepare()) before the serial work that precedes it (the picture
// of the others, the give-way claims), and the worker, woken then, spins for the run itself:
// it joins the run when it opens, and the run's notify is no system call. Between two runs of
// one step (the picture's per-entity part, then the moves) the caller asks the worker to stay
// awake (After::kAwait): one wake-up through the kernel a step. A worker does not otherwise
// spin after a run for the next: on a loaded machine the spinning worker used up its share of
// the core and lost it in the middle of a chunk, the caller then waiting milliseconds for it;
// on the idle machine spinning 500 us after every run gave no gain either (16.3x / 15.8x /
// 16.9x real time at 1,000 vehicles against 17.0x / 24.8x / 16.9x sleeping).

#include <atomic>
#include <chrono>
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

  /// Wakes the workers for a run that is about to start: they spin for it (kWorkerSpinWait at
  /// most) instead of being woken when it starts. Optional; only a hint.
  void prepare();

  /// What the workers do after a run: sleep until the next, or wait for it awake because the
  /// caller starts another soon (kWorkerSpinWait at most, as after prepare()).
  enum class After { kSleep, kAwait };

  /// Calls work(begin, end, worker) for chunks of at most `chunk` items covering [0, count),
  /// each exactly once, worker 0 on the calling thread (1.. on the pool's threads that join in
  /// time), and returns when all are done. An exception of any chunk is rethrown here. Two
  /// runs of the same `count` and `chunk` give each thread the same share of chunks first.
  void run(size_t count, size_t chunk, const std::function<void(size_t, size_t, unsigned)>& work,
           After after = After::kSleep);

 private:
  void serve(unsigned worker);
  /// Takes chunks until none is left; records the first exception.
  void drain(unsigned worker);
  /// Spins until a run after the `seen`-th starts, or `wait` has passed.
  void await_run(uint64_t seen, std::chrono::microseconds wait) const;

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_;
  const std::function<void(size_t, size_t, unsigned)>* work_ = nullptr;
  /// One thread's share of a run: the chunks [next, end), taken from the front, by the thread
  /// it belongs to and by the others once their own are done. On a cache line of its own.
  struct alignas(64) PoolShare {
    std::atomic<size_t> next{0};
    size_t end = 0;
  };

  size_t count_ = 0;
  size_t chunk_ = 1;
  std::vector<PoolShare> shares_;
  /// Runs started: changed under mutex_, read without it by the spinning workers.
  std::atomic<uint64_t> generation_{0};
  uint64_t prepared_ = 0;            ///< prepare() calls
  bool open_ = false;                ///< workers may still join the current run
  After after_ = After::kSleep;      ///< the current run's
  std::atomic<unsigned> active_{0};  ///< workers inside the current run (changed under mutex_)
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace corsa::engine::detail
