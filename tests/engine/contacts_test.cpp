// The contacts' update of the moved boxes alone (state/world_contacts.cpp): entities whose state
// is written without moving keep their boxes and pairs, a box that keeps its heading is made
// from its kept cosine and sine, and boxes touching at a corner alone are in contact; each
// update's pairs are checked against a test of every pair.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <utility>
#include <vector>

#include "contact_pairs.h"
#include "corsa/engine/oriented_box.h"
#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"
#include "state/world_contacts.h"
#include "test_entity.h"

namespace {

namespace detail = corsa::engine::detail;
using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;

// A state of `count` cars 4 m x 2 m (centred on their reference point) standing 10 m apart
// along x, unturned.
struct Cars {
  corsa::xosc::Scenario scenario;
  corsa::Diagnostics diagnostics;
  detail::SimState state{scenario, nullptr, corsa::engine::SimulationOptions{}, diagnostics};
  detail::ContactSweep sweep;

  explicit Cars(uint32_t count) {
    for (uint32_t i = 0; i < count; ++i) {
      detail::Entity entity = corsa::test::entity_of({0.0, 0.0, 0.75, 4.0, 2.0, 1.5});
      entity.write_state().placed = true;
      entity.write_state().pose.x = 10.0 * i;
      state.world.entities.push_back(std::move(entity));
    }
    detail::update_contacts(state, sweep);
  }
  detail::Entity& car(uint32_t i) { return state.world.entities[i]; }
  // One step: the contacts updated, and checked against a test of every pair.
  void step() {
    ++state.tick;
    detail::update_contacts(state, sweep);
    CHECK(state.contacts.pairs == corsa::test::pairs_by_testing_all(state.world.entities));
    CHECK(std::all_of(sweep.moved_mark.begin(), sweep.moved_mark.end(),
                      [](uint8_t mark) { return mark == 0; }));
  }
};

}  // namespace

TEST_CASE("A pair that starts touching after both stood still is a collision on that step",
          "[engine][contacts]") {
  Cars cars(8);
  REQUIRE(cars.state.contacts.pairs.empty());
  // Cars 2 and 3 stand for a while, their states written every step without a change of place
  // (their speed set to 0 again): nothing moves for the contacts.
  for (int k = 0; k < 5; ++k) {
    cars.car(2).write_state().speed = 0.0;
    cars.car(3).write_state().speed = 0.0;
    cars.step();
    CHECK(cars.sweep.moved.empty());
  }
  // Then car 2 rolls 6.5 m forward, into car 3's rear (0.5 m of overlap), keeping its heading.
  cars.car(2).write_state().pose.x += 6.5;
  cars.step();
  CHECK(cars.sweep.moved == std::vector<uint32_t>{2});
  CHECK(cars.state.contacts.pairs == Pairs{{2, 3}});
  REQUIRE(cars.state.collisions.size() == 1);
  CHECK(cars.state.collisions[0].first == 2);
  CHECK(cars.state.collisions[0].second == 3);
  CHECK(cars.state.collisions[0].tick == cars.state.tick);
  // Both stand again, written without a change: the contact stays, no new collision.
  for (int k = 0; k < 3; ++k) {
    cars.car(2).write_state().speed = 0.0;
    cars.car(3).write_state().speed = 0.0;
    cars.step();
  }
  CHECK(cars.state.contacts.pairs == Pairs{{2, 3}});
  CHECK(cars.state.collisions.size() == 1);
  // Car 3 turns in place (a new heading) and clears car 2: the contact ends.
  cars.car(3).write_state().pose.h = 0.5;
  cars.car(3).write_state().pose.y += 3.0;
  cars.step();
  CHECK(cars.state.contacts.pairs.empty());
  // Car 3 comes back across, turned, onto car 2's front: a second collision of the pair.
  cars.car(3).write_state().pose.y -= 3.0;
  cars.step();
  CHECK(cars.state.contacts.pairs == Pairs{{2, 3}});
  REQUIRE(cars.state.collisions.size() == 2);
  CHECK(cars.state.collisions[1].tick == cars.state.tick);
}

TEST_CASE("Boxes touching only at a corner are in contact, moved alone or all at once",
          "[engine][contacts]") {
  // Unturned 4 m x 2 m boxes: extents exact in binary, so a corner lands exactly on a corner.
  for (const bool all_move : {false, true}) {
    CAPTURE(all_move);
    Cars cars(40);
    // Car 5 moves to touch car 6 at a corner alone: at (56, -2) its box spans x 54 to 58 and y
    // -3 to -1; car 6 at (60, 0) spans x 58 to 62 and y -1 to 1: they share the point (58, -1).
    cars.car(5).write_state().pose.x = 56.0;
    cars.car(5).write_state().pose.y = -2.0;
    if (all_move) {
      // Every other car moves a little too: the update then sweeps every box.
      for (uint32_t i = 0; i < 40; ++i) {
        if (i != 5 && i != 6) cars.car(i).write_state().pose.y += 0.25;
      }
    }
    cars.step();
    CHECK(cars.sweep.moved.size() == (all_move ? 39u : 1u));
    CHECK(cars.state.contacts.pairs == Pairs{{5, 6}});
    REQUIRE(cars.state.collisions.size() == 1);
    // Half a metre further back along x, the corners part.
    cars.car(5).write_state().pose.x = 55.5;
    cars.step();
    CHECK(cars.state.contacts.pairs.empty());
    // Car 6 moves back onto the corner, car 5 standing: x 57.5 to 61.5.
    cars.car(6).write_state().pose.x = 59.5;
    cars.step();
    CHECK(cars.state.contacts.pairs == Pairs{{5, 6}});
    CHECK(cars.state.collisions.size() == 2);
  }
}

TEST_CASE("A box moved keeping its heading is the box box_of makes", "[engine][contacts]") {
  Cars cars(3);
  for (const double h : {0.3, 0.3, -2.1, -2.1, -2.1}) {
    cars.car(1).write_state().pose.h = h;
    cars.car(1).write_state().pose.x += 0.7;
    cars.car(1).write_state().pose.y += 0.4;
    cars.step();
    const detail::Entity& car = cars.car(1);
    const corsa::engine::OrientedBox made = corsa::engine::box_of(car.info.box, car.state().pose);
    const corsa::engine::OrientedBox& kept = cars.state.contacts.boxes[1];
    CHECK(kept.cx == made.cx);
    CHECK(kept.cy == made.cy);
    CHECK(kept.cos_h == made.cos_h);
    CHECK(kept.sin_h == made.sin_h);
    CHECK(kept.z_min == made.z_min);
    CHECK(kept.z_max == made.z_max);
  }
}
