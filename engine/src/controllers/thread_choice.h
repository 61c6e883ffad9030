#pragma once

// Whether a step's moves go to the worker pool's threads or stay on the calling thread: the one
// that has been faster on this machine lately, measured. Which threads move the entities
// changes no result (controllers/worker_pool.h), so the choice may follow the clock.
//
// On the shared virtual machine two threads were faster than one only at times: 1,000 vehicles
// on Town04 ran 19.0x / 18.3x / 19.0x real time on one thread and 17.0x / 24.8x / 16.9x on two
// (docs/performance/two-threads.md). Handing half a step to the other virtual CPU costs its wake-up
// and the moved entities' cache lines crossing between the cores; whether the half spared pays
// for that depends on what the hypervisor and the machine's other programs do, not on anything
// a table of sizes could hold. So every kProbePeriod steps the run times kBlocks blocks of
// steps each way, alternated (the machine's own speed drifts over tens of milliseconds: the
// two ways then see the same drift), and keeps the faster way until the next probe.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>

namespace corsa::engine::detail {

class ThreadChoice {
 public:
  using Duration = std::chrono::steady_clock::duration;

  /// Whether the coming step is to be shared out among the threads.
  bool shared() const { return shared_; }

  /// Charges a step's wall time (the whole step, not only its moves: the serial phases read
  /// what the other core wrote) to the way it went, shared() or not, and picks the next way.
  void charge(Duration step);

  /// A probe: kBlocks blocks of kBlockSteps steps each way, shared first, alternated; the
  /// first kWarmSteps of a block are not counted (they pay for the switch itself: the caches
  /// and the worker's wake-up).
  static constexpr uint32_t kBlockSteps = 6;
  static constexpr uint32_t kWarmSteps = 2;
  static constexpr uint32_t kBlocks = 3;
  static constexpr uint32_t kProbeSteps = 2 * kBlocks * kBlockSteps;
  /// Steps counted of each way in a probe.
  static constexpr uint32_t kTrialSteps = kBlocks * (kBlockSteps - kWarmSteps);
  /// Steps from one probe's start to the next.
  static constexpr uint32_t kProbePeriod = 400;

 private:
  /// The median of one way's counted steps: a step that lost its core to another program for
  /// a while does not decide.
  static Duration median(std::array<Duration, kTrialSteps>& steps);

  bool shared_ = true;  ///< a run starts with a probe's shared block
  uint32_t step_ = 0;   ///< steps since the probe began
  /// The probe's counted steps: [0] shared, [1] on one thread.
  std::array<std::array<Duration, kTrialSteps>, 2> trial_{};
};

}  // namespace corsa::engine::detail
