#include "controllers/thread_choice.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>

using corsa::engine::detail::ThreadChoice;
using std::chrono::microseconds;

namespace {

// Charges the steps of one probe: `shared` for each shared step, `alone` for the others, with
// `spike` instead every fifth step (a step that lost its core for a while), and `warm` for the
// first steps of each block (not counted). Returns the way chosen for the rest of the period.
bool probe(ThreadChoice& choice, microseconds shared, microseconds alone, microseconds spike,
           microseconds warm = microseconds{100'000}) {
  for (uint32_t step = 0; step < ThreadChoice::kProbeSteps; ++step) {
    // Blocks alternate, shared first.
    REQUIRE(choice.shared() == (step / ThreadChoice::kBlockSteps % 2 == 0));
    const bool warming = step % ThreadChoice::kBlockSteps < ThreadChoice::kWarmSteps;
    choice.charge(warming ? warm : step % 5 == 4 ? spike : (choice.shared() ? shared : alone));
  }
  return choice.shared();
}

// The steps after a probe until the next one begins (the probe's steps are counted).
void settle(ThreadChoice& choice, bool chosen) {
  for (uint32_t step = ThreadChoice::kProbeSteps; step < ThreadChoice::kProbePeriod; ++step) {
    REQUIRE(choice.shared() == chosen);
    choice.charge(microseconds{1});
  }
}

}  // namespace

TEST_CASE(
    "The thread choice times blocks of steps each way, alternated, keeps the faster until the next "
    "probe and is not swayed by steps that lost their core or paid for a switch",
    "[engine][traffic]") {
  ThreadChoice choice;
  // Shared steps faster: shared kept, although a fifth of the steps took 10 ms and the blocks'
  // first steps 100 ms.
  CHECK(probe(choice, microseconds{300}, microseconds{500}, microseconds{10'000}));
  settle(choice, true);
  // The next probe starts shared again; now the steps alone are faster.
  CHECK_FALSE(probe(choice, microseconds{600}, microseconds{520}, microseconds{5}));
  settle(choice, false);
  // And back: a period's choice is only that period's.
  CHECK(probe(choice, microseconds{200}, microseconds{520}, microseconds{520}, microseconds{1}));
  settle(choice, true);
  CHECK(choice.shared());
}
