#include "controllers/thread_choice.h"

namespace corsa::engine::detail {

ThreadChoice::Duration ThreadChoice::median(std::array<Duration, kTrialSteps>& steps) {
  std::nth_element(steps.begin(), steps.begin() + kTrialSteps / 2, steps.end());
  return steps[kTrialSteps / 2];
}

void ThreadChoice::charge(Duration step) {
  const uint32_t at = step_++;
  if (at < kProbeSteps) {
    // Block b (shared when even) of the probe, step k of the block.
    const uint32_t block = at / kBlockSteps;
    const uint32_t k = at % kBlockSteps;
    if (k >= kWarmSteps) {
      trial_[block % 2][block / 2 * (kBlockSteps - kWarmSteps) + k - kWarmSteps] = step;
    }
    if (at + 1 < kProbeSteps) {
      shared_ = (at + 1) / kBlockSteps % 2 == 0;
    } else {
      shared_ = median(trial_[0]) < median(trial_[1]);
    }
    return;
  }
  if (step_ == kProbePeriod) {
    step_ = 0;
    shared_ = true;
  }
}

}  // namespace corsa::engine::detail
