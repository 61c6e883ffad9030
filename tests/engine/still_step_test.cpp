// The default controller skips the step of an entity standing on its lane while nothing of its
// motion has changed since a step that changed nothing (state/entity.h, Entity::still_step). Each
// test steps two copies of one entity through the same changes, one that may skip and one whose
// memo is cleared before every step (so that it takes every step in full): their motions must
// hold the same bits after every step.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../xodr/xodr_test_util.h"
#include "actions/route_assignment.h"
#include "lanes/lane_follow.h"
#include "motion/controller.h"
#include "state/sim_state.h"

namespace {

using corsa::engine::detail::DefaultController;
using corsa::engine::detail::Entity;
using corsa::engine::detail::EntityMotion;
using corsa::engine::detail::LaneFollow;
using corsa::engine::detail::MotionContext;
using corsa::xodr::Map;

constexpr double kStillStepDt = 0.01;

// The engine's comparison of bits (state/sim_state.h), by a name of this file's own (a unity
// batch may hold another test's `same_bits`).
template <class T>
bool bits_equal(const T& a, const T& b) {
  return corsa::engine::detail::same_bits(a, b);
}

bool still_step_same_lane(const LaneFollow& a, const LaneFollow& b) {
  return a.on_road == b.on_road && a.road == b.road && a.section == b.section && a.lane == b.lane &&
         a.node == b.node && bits_equal(a.s, b.s) && a.dir == b.dir &&
         bits_equal(a.lateral, b.lateral) && bits_equal(a.heading_offset, b.heading_offset) &&
         bits_equal(a.frame_shift, b.frame_shift);
}

// Every field of the motion, bit for bit (padding left out).
bool still_step_same_motion(const EntityMotion& a, const EntityMotion& b) {
  const auto& x = a.state();
  const auto& y = b.state();
  return bits_equal(x.pose, y.pose) && bits_equal(x.speed, y.speed) &&
         bits_equal(x.acceleration, y.acceleration) &&
         bits_equal(x.lateral_speed, y.lateral_speed) && bits_equal(x.yaw_rate, y.yaw_rate) &&
         bits_equal(x.odometer, y.odometer) && x.placed == y.placed && x.visible == y.visible &&
         bits_equal(x.road, y.road) && still_step_same_lane(a.lane, b.lane) &&
         bits_equal(a.speed_command, b.speed_command) &&
         bits_equal(a.lateral_command, b.lateral_command) &&
         bits_equal(a.longitudinal_distance, b.longitudinal_distance) &&
         bits_equal(a.lateral_acceleration, b.lateral_acceleration) &&
         a.end_of_road == b.end_of_road && a.chooser == b.chooser;
}

// Two copies of an entity on the right lane (-1) of straight_500m's only road at `s`, facing +s:
// `skipping` steps as the engine steps it, `full` takes every step in full.
struct StillStepPair {
  Map map = corsa::xodr::test::load_map(corsa::xodr::test::shared_map("straight_500m.xodr"));
  std::vector<corsa::xodr::LaneSpan> scratch;
  MotionContext context;
  DefaultController controller;
  Entity skipping;
  Entity full;
  int skipped_steps = 0;  ///< steps begun with a memo the entity still held

  explicit StillStepPair(double s) {
    context.map = &map;
    context.dt = kStillStepDt;
    context.scratch = &scratch;
    teleport(s);
  }

  // What a TeleportAction does to both: a new place on the lane, the pose from it.
  void teleport(double s) {
    for (Entity* entity : {&skipping, &full}) {
      const auto t = corsa::engine::detail::lane_center_t(map, 0, s, -1);
      REQUIRE(t);
      REQUIRE(corsa::engine::detail::attach_to_lane(map, entity->lane, 0, s, *t, -1, 0.0));
      entity->write_state().placed = true;
      // Asked to stay where it was put across its lane (the attachment's offset, a rounding off
      // the centre), so that it stands from the first step.
      entity->lateral_command = entity->lane.lateral;
      corsa::engine::detail::update_pose_from_lane(*entity, map, scratch);
    }
  }

  // The same change to both copies, then one step of each; their motions must agree.
  void step(const std::function<void(Entity&)>& change = {}) {
    if (change) {
      change(skipping);
      change(full);
    }
    skipped_steps +=
        skipping.still_step_valid && still_step_same_motion(skipping.still_step, skipping);
    full.still_step_valid = false;
    controller.step(skipping, context);
    controller.step(full, context);
    REQUIRE(still_step_same_motion(skipping, full));
  }
};

// What an AssignRouteAction does: both copies follow one new route (a route of no steps; the
// default controller's step only hands it to the lane ends it meets).
void still_step_assign_route(StillStepPair& pair) {
  corsa::engine::detail::assign_route(pair.skipping, corsa::engine::detail::RoutePlan{});
  pair.full.route = pair.skipping.route;
  pair.full.chooser = pair.skipping.chooser;
  pair.full.route_progress = pair.skipping.route_progress;
}

}  // namespace

TEST_CASE("A standing entity's step is skipped, and any change of its motion ends the skip",
          "[engine][motion][still]") {
  StillStepPair pair(100.0);
  for (int i = 0; i < 10; ++i) {
    pair.step();
  }
  // The first step stood and was remembered; the nine after it were skipped.
  CHECK(pair.skipped_steps == 9);
  CHECK(pair.skipping.still_step_valid);
  const double s_before = pair.skipping.lane.s;

  SECTION("a speed asked for later moves it on the next step") {
    pair.step([](Entity& e) { e.speed_command = 5.0; });
    CHECK(pair.skipping.state().speed == 5.0);
    CHECK(pair.skipping.lane.s == Approx(s_before + 5.0 * kStillStepDt).margin(1e-12));
    CHECK_FALSE(pair.skipping.still_step_valid);  // a moving entity is not remembered
    for (int i = 0; i < 20; ++i) {
      pair.step();
    }
    CHECK(pair.skipping.lane.s == Approx(s_before + 21 * 5.0 * kStillStepDt).margin(1e-9));
    // Asked to stop: it stands on the next step; the step after that still changes its
    // acceleration (to 0), the third changes nothing and is remembered, the fourth is skipped.
    const int skipped = pair.skipped_steps;
    pair.step([](Entity& e) { e.speed_command = 0.0; });
    CHECK(pair.skipping.state().speed == 0.0);
    CHECK(pair.skipping.state().acceleration == Approx(-5.0 / kStillStepDt));
    pair.step();
    pair.step();
    CHECK(pair.skipped_steps == skipped);
    pair.step();
    CHECK(pair.skipped_steps == skipped + 1);
  }
  SECTION("a lateral offset asked for later moves it across its lane") {
    pair.step([](Entity& e) { e.lateral_command = 0.4; });
    CHECK(pair.skipping.lane.lateral == 0.4);
    CHECK(pair.skipping.state().lateral_speed == Approx(0.4 / kStillStepDt));
    pair.step();
    CHECK(pair.skipping.state().lateral_speed == 0.0);  // the offset reached: standing again
  }
  SECTION("a speed written into its state by an action is taken back to the command") {
    pair.step([](Entity& e) { e.write_state().speed = 3.0; });
    CHECK(pair.skipping.state().speed == 0.0);
    CHECK(pair.skipping.state().acceleration == Approx(-3.0 / kStillStepDt));
  }
  SECTION("a teleport takes it to the new place and it stands there") {
    pair.teleport(250.0);
    pair.step();
    CHECK(pair.skipping.lane.s == 250.0);
    pair.step();
    CHECK(pair.skipping.still_step_valid);
  }
  SECTION("a speed command of -0 differs from one of +0, to the bit") {
    const int skipped = pair.skipped_steps;
    pair.step([](Entity& e) { e.speed_command = -0.0; });
    CHECK(pair.skipped_steps == skipped);  // taken in full: the command's bits changed
    // The speed turns -0, then its change (the acceleration) turns +0: standing again, the
    // motion is remembered with -0 and skipped from the fourth step on.
    for (int i = 0; i < 3; ++i) {
      pair.step();
    }
    const int skipped_at_minus = pair.skipped_steps;
    CHECK(skipped_at_minus > skipped);
    CHECK(std::signbit(pair.skipping.state().speed));
    pair.step([](Entity& e) { e.speed_command = 0.0; });
    CHECK(pair.skipped_steps == skipped_at_minus);
    CHECK(pair.skipping.lane.s == s_before);
  }
  SECTION("a NaN speed command equals itself, to the bit") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const int skipped = pair.skipped_steps;
    pair.step([nan](Entity& e) { e.speed_command = nan; });
    CHECK(pair.skipped_steps == skipped);  // taken in full: the command's bits changed
    for (int i = 0; i < 5; ++i) {
      pair.step();
    }
    // Both copies hold the same bits after every step (checked by step); whether the NaN step
    // is remembered follows from the motion it leaves, the same for both.
    CHECK(std::isnan(pair.skipping.speed_command));
  }
  SECTION("an odometer or distance set from outside is kept") {
    pair.step([](Entity& e) { e.longitudinal_distance = 12.5; });
    pair.step([](Entity& e) { e.write_state().odometer = 7.0; });
    CHECK(pair.skipping.longitudinal_distance == 12.5);
    CHECK(pair.skipping.state().odometer == 7.0);
  }
  for (int i = 0; i < 5; ++i) {
    pair.step();
  }
}

TEST_CASE("A car held at a road's end keeps asking for its speed until it is put elsewhere",
          "[engine][motion][still]") {
  StillStepPair pair(499.0);
  // 10 m/s: 0.1 m a step, at the road's end (500 m, no successor) after ten steps.
  for (int i = 0; i < 30; ++i) {
    pair.step([i](Entity& e) {
      if (i == 0) {
        e.speed_command = 10.0;
      }
    });
  }
  CHECK(pair.skipping.end_of_road);
  CHECK(pair.skipping.state().speed == 0.0);
  CHECK(pair.skipping.speed_command == 10.0);
  CHECK(pair.skipped_steps > 10);
  CHECK(pair.skipping.still_step_valid);

  // A route given while it stands at the dead end: the memo is dropped and the next step is
  // taken in full, though the route leads nowhere here either.
  int skipped = pair.skipped_steps;
  still_step_assign_route(pair);
  CHECK_FALSE(pair.skipping.still_step_valid);
  pair.step();
  CHECK(pair.skipped_steps == skipped);
  CHECK(pair.skipping.end_of_road);
  pair.step();
  pair.step();
  CHECK(pair.skipped_steps > skipped);  // remembered again with the route, then skipped
  // Two routes in a row: the first is freed when the second replaces it, and the second may
  // take the address of the route the memo held. The skip ends all the same.
  skipped = pair.skipped_steps;
  still_step_assign_route(pair);
  still_step_assign_route(pair);
  pair.step();
  CHECK(pair.skipped_steps == skipped);
  const double odometer = pair.skipping.state().odometer;
  // Put back on the road: it drives on at the speed it still asks for.
  pair.teleport(300.0);
  pair.step();
  CHECK_FALSE(pair.skipping.end_of_road);
  CHECK(pair.skipping.state().speed == 10.0);
  CHECK(pair.skipping.lane.s == Approx(300.0 + 10.0 * kStillStepDt).margin(1e-9));
  CHECK(pair.skipping.state().odometer == Approx(odometer + 10.0 * kStillStepDt).margin(1e-9));
}

TEST_CASE("The memos' comparisons tell every compared double's bits apart, and a NaN equals itself",
          "[engine][motion][still]") {
  using corsa::engine::detail::ContactInput;
  using corsa::engine::detail::same_bits;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Each double of the motion's runs compared as words: -0 against +0 differs, and the
  // same NaN is the same.
  const std::vector<std::function<double&(EntityMotion&)>> fields = {
      [](EntityMotion& m) -> double& { return m.write_state().pose.x; },
      [](EntityMotion& m) -> double& { return m.write_state().pose.r; },
      [](EntityMotion& m) -> double& { return m.write_state().speed; },
      [](EntityMotion& m) -> double& { return m.write_state().odometer; },
      [](EntityMotion& m) -> double& { return m.speed_command; },
      [](EntityMotion& m) -> double& { return m.lateral_acceleration; },
  };
  for (const auto& field : fields) {
    EntityMotion a, b;
    field(b) = -0.0;
    CHECK_FALSE(same_bits(a, b));
    field(a) = nan;
    field(b) = nan;
    CHECK(same_bits(a, b));
  }
  // The contacts' input: placed, x, y, z and h; pitch and roll take no part, nor the box (fixed
  // once the entity exists: no write of it compiles).
  static_assert(!std::is_assignable_v<decltype((std::declval<Entity&>().info.box)),
                                      const corsa::engine::Box&>);
  static_assert(!std::is_assignable_v<decltype((std::declval<Entity&>().info.box.length)), double>);
  static_assert(!std::is_assignable_v<decltype((std::declval<Entity&>().info)),
                                      const corsa::engine::EntityInfo&>);
  static_assert(!std::is_move_assignable_v<Entity>);  // nor is an entity assigned over another
  const auto placed_entity = [](const std::function<void(Entity&)>& change) {
    corsa::engine::EntityInfo info;
    info.box = {1.0, 0.0, 0.5, 4.0, 2.0, 1.5};
    Entity entity(std::move(info));
    entity.write_state().placed = true;
    change(entity);
    return entity;
  };
  const Entity entity = placed_entity([](Entity&) {});
  const ContactInput input(entity);
  CHECK(input.same_as(entity));
  CHECK(input.same_as(placed_entity([](Entity& e) { e.write_state().pose.p = 0.1; })));
  CHECK_FALSE(input.same_as(placed_entity([](Entity& e) { e.write_state().pose.h = -0.0; })));
  CHECK_FALSE(input.same_as(placed_entity([](Entity& e) { e.write_state().placed = false; })));
}

TEST_CASE("The memos pass over a state whose count of writes stands, and compare the rest",
          "[engine][motion][still]") {
  using corsa::engine::detail::ContactInput;
  // The contacts' input of an entity: with its count standing, the state is the one taken (no
  // more is compared); a write that changes nothing moves the count, and the state is compared.
  Entity entity;
  entity.write_state().placed = true;
  const ContactInput input(entity);
  CHECK(input.same_as(entity));
  entity.write_state().pose.x = 0.0;
  CHECK(input.same_as(entity));
  entity.write_state().pose.x = 1e-9;
  CHECK_FALSE(input.same_as(entity));

  // The still step: a motion changed beside the state (its count standing) ends the skip, and
  // the step is taken in full (which writes the state: its count moves); a write of the state
  // that changes nothing does not end it (the skipped step leaves the count where it was).
  StillStepPair pair(100.0);
  for (int i = 0; i < 3; ++i) {
    pair.step();
  }
  REQUIRE(pair.skipping.still_step_valid);
  uint32_t count = pair.skipping.state_changes();
  pair.step();
  CHECK(pair.skipping.state_changes() == count);  // skipped
  const double x = pair.skipping.state().pose.x;
  pair.step([](Entity& e) { e.lane.s += 1.0; });
  CHECK(pair.skipping.state_changes() != count);  // taken in full
  CHECK(pair.skipping.state().pose.x != x);
  pair.step();  // remembered again
  pair.step();
  count = pair.skipping.state_changes();
  pair.step([](Entity& e) { e.write_state().speed = e.state().speed; });
  CHECK(pair.skipping.state_changes() == count + 1);  // the write alone: skipped
  pair.step([](Entity& e) { e.speed_command = 1.0; });
  CHECK(pair.skipping.state_changes() > count + 1);
}

TEST_CASE("The still step's test of the motion sees each field beside the state, and no padding",
          "[engine][motion][still]") {
  // A step taken in full writes the state (its count of writes grows); a skipped one does not.
  const auto taken = [](StillStepPair& pair, const std::function<void(Entity&)>& change) {
    const uint32_t before = pair.skipping.state_changes();
    pair.step(change);
    return pair.skipping.state_changes() != before;
  };
  StillStepPair pair(100.0);
  for (int i = 0; i < 3; ++i) {
    pair.step();
  }
  REQUIRE(pair.skipping.still_step_valid);
  REQUIRE_FALSE(taken(pair, {}));

  SECTION("a change of one bit of any field is a step taken") {
    const std::vector<std::pair<std::string, std::function<void(Entity&)>>> changes = {
        {"s", [](Entity& e) { e.lane.s = std::nextafter(e.lane.s, 1e9); }},
        {"lateral", [](Entity& e) { e.lane.lateral = std::nextafter(e.lane.lateral, 1.0); }},
        {"heading_offset", [](Entity& e) { e.lane.heading_offset = -0.0; }},
        {"frame_shift", [](Entity& e) { e.lane.frame_shift = -0.0; }},
        {"dir", [](Entity& e) { e.lane.dir = -e.lane.dir; }},
        {"on_road", [](Entity& e) { e.lane.on_road = false; }},
        {"speed_command", [](Entity& e) { e.speed_command = -0.0; }},
        {"lateral_command", [](Entity& e) { e.lateral_command = e.lane.lateral + 1e-3; }},
        {"longitudinal_distance", [](Entity& e) { e.longitudinal_distance = 1e-300; }},
        {"lateral_acceleration", [](Entity& e) { e.lateral_acceleration = 0.5; }},
        {"end_of_road", [](Entity& e) { e.end_of_road = !e.end_of_road; }},
    };
    for (const auto& [field, change] : changes) {
      StillStepPair fresh(100.0);
      for (int i = 0; i < 3; ++i) {
        fresh.step();
      }
      REQUIRE(fresh.skipping.still_step_valid);
      INFO(field);
      CHECK(taken(fresh, change));
    }
  }
  SECTION("bytes of padding that differ from the memo's leave the step skipped") {
    // LaneFollow's padding: after on_road (bytes 1-3), after node (20-23), after dir (36-39).
    static_assert(sizeof(LaneFollow) == 64);
    const auto scribble = [](Entity& e) {
      auto* bytes = reinterpret_cast<unsigned char*>(&e.lane);
      for (const size_t at : {1, 2, 3, 20, 21, 22, 23, 36, 37, 38, 39}) {
        bytes[at] = static_cast<unsigned char>(bytes[at] ^ 0x5a);
      }
    };
    CHECK_FALSE(taken(pair, scribble));
    CHECK_FALSE(taken(pair, {}));
  }
}
