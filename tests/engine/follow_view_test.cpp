// The picture of the others (controllers/follow_view.h) taken in parts: the entities' own parts
// filled on several threads, in any order, and gathered on one give the picture that one thread
// builds, to the bit.

#include "controllers/follow_view.h"

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "controllers/worker_pool.h"
#include "corsa/engine/simulation.h"
#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"
#include "test_entity.h"

namespace {

namespace detail = corsa::engine::detail;
using corsa::Diagnostics;
using corsa::engine::Box;
using corsa::engine::SimulationOptions;

// The fields of a target that the picture set for its entity, as bits.
std::vector<uint64_t> bits_of(const detail::FollowTarget& t) {
  std::vector<uint64_t> bits;
  if (!t.present) {
    return {t.usable, t.generated};
  }
  for (const double v : {t.x, t.y, t.h, t.speed, t.rear, t.length, t.shape.cx, t.shape.cy,
                         t.shape.half_length, t.shape.half_width, t.shape.cos_h, t.shape.sin_h}) {
    bits.push_back(std::bit_cast<uint64_t>(v));
  }
  bits.insert(bits.end(), {t.usable, t.generated, t.vehicle});
  return bits;
}

}  // namespace

TEST_CASE("A picture filled on two threads in another order is the one built on one",
          "[engine][traffic]") {
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (uint32_t i = 0; i < 600; ++i) {
    const double x = 500.0 * unit(random);
    const double y = 300.0 * unit(random);
    const double h = 6.3 * unit(random);
    const double speed = 20.0 * unit(random);
    const Box box{1.4 * unit(random), 0.0, 0.75, i % 7 == 0 ? 12.0 : 4.5, 1.9, 1.5};
    detail::Entity entity = corsa::test::entity_of(box);
    // Some not placed, and some made by traffic.
    entity.write_state().placed = i % 11 != 0;
    entity.write_state().pose.x = x;
    entity.write_state().pose.y = y;
    entity.write_state().pose.h = h;
    entity.write_state().speed = speed;
    state.world.entities.push_back(std::move(entity));
    if (i % 3 == 0) {
      state.traffic.lifetimes[i];
    }
  }
  detail::FollowView one;
  one.build(state, true);
  // The entities in a shuffled order, filled on two threads as the moves share them out.
  std::vector<uint32_t> order(state.world.entities.size());
  for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), random);
  detail::WorkerPool pool(2);
  detail::FollowView two;
  for (int step = 0; step < 3; ++step) {  // the records are reused from step to step
    two.begin(state, true);
    pool.run(
        order.size(), 32,
        [&](size_t begin, size_t end, unsigned) {
          for (size_t k = begin; k < end; ++k) two.fill(state, order[k]);
        },
        detail::WorkerPool::After::kAwait);
    two.finish();
    REQUIRE(two.targets().size() == one.targets().size());
    size_t same = 0;
    for (size_t i = 0; i < one.targets().size(); ++i) {
      same += bits_of(one.targets()[i]) == bits_of(two.targets()[i]) ? 1 : 0;
    }
    CHECK(same == one.targets().size());
    CHECK(std::bit_cast<uint64_t>(two.least_rear()) == std::bit_cast<uint64_t>(one.least_rear()));
    CHECK(two.max_reach() == one.max_reach());
    CHECK(two.max_offset() == one.max_offset());
    CHECK(two.max_length() == one.max_length());
    CHECK(two.unindexed() == one.unindexed());
    std::vector<uint32_t> near_one;
    std::vector<uint32_t> near_two;
    one.near(100.0, 50.0, 200.0, 150.0, near_one);
    two.near(100.0, 50.0, 200.0, 150.0, near_two);
    CHECK_FALSE(near_one.empty());
    CHECK(near_two == near_one);  // the same grid: the same answer in the same order
  }
}
