#include "controllers/thread_choice.h"

namespace corsa::engine::detail {

ThreadChoice::Duration ThreadChoice::trial_median() {
  std::nth_element(trial_.begin(), trial_.begin() + kTrialSteps / 2, trial_.end());
  return trial_[kTrialSteps / 2];
}

void ThreadChoice::charge(Duration step) {
  // A probe: kWarmSteps + kTrialSteps shared, as many on this thread alone, then the faster way
  // until kProbePeriod steps have passed since the probe began.
  constexpr uint32_t kTrial = kWarmSteps + kTrialSteps;
  const uint32_t at = step_++;
  if (at < 2 * kTrial) {
    const uint32_t in_trial = at % kTrial;
    if (in_trial >= kWarmSteps) {
      trial_[in_trial - kWarmSteps] = step;
    }
    if (in_trial + 1 == kTrial) {
      if (at < kTrial) {
        shared_median_ = trial_median();
        shared_ = false;
      } else {
        shared_ = shared_median_ < trial_median();
      }
    }
    return;
  }
  if (step_ == kProbePeriod) {
    step_ = 0;
    shared_ = true;
  }
}

}  // namespace corsa::engine::detail
