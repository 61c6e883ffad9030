// A default-controller step whose travel is far below an ulp of the lane's s (a speed decaying
// toward 0 that an action keeps setting, as a continuous relative SpeedAction behind a slowing
// car does) leaves the lane position and the pose as they are, without asking the lane graph or
// the reference line (motion/default_controller.cpp, creeps_in_place). Each test drives an
// entity, lets it creep, then drives it again, beside a twin that never creeps: the creeping
// steps change nothing but the speed and what follows from it, and the later motion is the
// twin's to the bit.

#include <catch2/catch.hpp>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string>
#include <vector>

#include "../xodr/xodr_test_util.h"
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

constexpr double kCreepDt = 0.01;

// The engine's comparison of bits (state/sim_state.h), by a name of this file's own (a unity
// batch may hold another test's).
template <class T>
bool creep_bits_equal(const T& a, const T& b) {
  return corsa::engine::detail::same_bits(a, b);
}

// An entity on `lane` of road 0 of a map at `s`, facing along the lane's s (heading_offset 0)
// or against it, asked to hold its place across the lane.
struct CreepDriver {
  Map map;
  std::vector<corsa::xodr::LaneSpan> scratch;
  MotionContext context;
  DefaultController controller;
  Entity entity;

  CreepDriver(const std::string& map_name, int lane, double s, bool against_s)
      : map(corsa::xodr::test::load_map(corsa::xodr::test::shared_map(map_name))) {
    context.map = &map;
    context.dt = kCreepDt;
    context.scratch = &scratch;
    const auto t = corsa::engine::detail::lane_center_t(map, 0, s, lane);
    REQUIRE(t);
    const double road_heading = map.reference(0, s).hdg;
    REQUIRE(corsa::engine::detail::attach_to_lane(
        map, entity.lane, 0, s, *t, lane, road_heading + (against_s ? std::numbers::pi : 0.0)));
    entity.write_state().placed = true;
    entity.lateral_command = entity.lane.lateral;
    corsa::engine::detail::update_pose_from_lane(entity, map, scratch);
  }

  void step(double speed) {
    entity.speed_command = speed;
    controller.step(entity, context);
  }
};

// Where the entity is and what it has driven, bit for bit.
bool same_place(const EntityMotion& a, const EntityMotion& b) {
  return creep_bits_equal(a.lane, b.lane) && creep_bits_equal(a.state().pose, b.state().pose) &&
         creep_bits_equal(a.state().road, b.state().road) &&
         creep_bits_equal(a.state().odometer, b.state().odometer) &&
         creep_bits_equal(a.longitudinal_distance, b.longitudinal_distance) &&
         creep_bits_equal(a.lateral_command, b.lateral_command) && a.end_of_road == b.end_of_road;
}

// The rates of a step that did not move: no heading change, no lateral motion.
bool still_rates(const EntityMotion& motion) {
  return creep_bits_equal(motion.state().yaw_rate, 0.0) &&
         creep_bits_equal(motion.state().lateral_speed, 0.0) &&
         creep_bits_equal(motion.lateral_acceleration, 0.0);
}

void check_creep_then_drive(const std::string& map_name, int lane, double s, bool against_s) {
  CreepDriver creeping(map_name, lane, s, against_s);
  CreepDriver twin(map_name, lane, s, against_s);
  for (int i = 0; i < 50; ++i) {
    creeping.step(10.0);
    twin.step(10.0);
  }
  REQUIRE(creep_bits_equal<EntityMotion>(creeping.entity, twin.entity));
  const EntityMotion before = creeping.entity;
  REQUIRE(before.state().odometer == Approx(5.0));

  // 1e-40 m/s and the like: travels of 1e-42 m, some 1e-28 of an ulp of s.
  double previous = 10.0;
  for (const double speed : {1e-40, 1e-40, 3e-41, -2e-41, 1e-45, 7e-44}) {
    creeping.step(speed);
    const EntityMotion& now = creeping.entity;
    CHECK(same_place(now, before));
    CHECK(still_rates(now));
    CHECK(creep_bits_equal(now.state().speed, speed));
    CHECK(creep_bits_equal(now.state().acceleration, (speed - previous) / kCreepDt));
    // What the full step would have done with such a travel: the lane position stays, for any
    // scale of the path to the reference line ([0.2, 5]).
    for (const double scale : {0.2, 1.0, 5.0}) {
      LaneFollow advanced = before.lane;
      const auto moved = corsa::engine::detail::advance_along_lanes(
          creeping.map, advanced, speed * kCreepDt / scale, nullptr);
      CHECK(creep_bits_equal(advanced, before.lane));
      CHECK_FALSE(moved.hit_end);
    }
    previous = speed;
  }

  // A real speed again: it drives on exactly as the twin, which never crept.
  for (int i = 0; i < 20; ++i) {
    creeping.step(5.0);
    twin.step(5.0);
  }
  CHECK(creep_bits_equal<EntityMotion>(creeping.entity, twin.entity));
  CHECK(creeping.entity.state().odometer == Approx(6.0));
  CHECK(std::abs(creeping.entity.lane.s - s) == Approx(6.0).margin(0.05));
}

}  // namespace

TEST_CASE("A step far below an ulp of s keeps the pose and the lane, the speed follows",
          "[engine][motion][creep]") {
  SECTION("on a straight road, along s") {
    check_creep_then_drive("straight_500m.xodr", -1, 100.0, false);
  }
  SECTION("on a straight road, against s") {
    check_creep_then_drive("straight_500m.xodr", -1, 300.0, true);
  }
  // e6mini's road 0 bends (paramPoly3): the path is scaled to the reference line there.
  SECTION("on a curved road, in an outer lane") {
    check_creep_then_drive("e6mini.xodr", -3, 300.0, false);
  }
}

TEST_CASE("A travel that does reach s moves the entity, however small the speed",
          "[engine][motion][creep]") {
  CreepDriver driver("straight_500m.xodr", -1, 100.0, false);
  for (int i = 0; i < 10; ++i) {
    driver.step(10.0);
  }
  const double s_before = driver.entity.lane.s;
  // Two ulps of s (at 101 m) in one step: not creeping, s moves by them.
  const double ulp = std::nextafter(s_before, 1e9) - s_before;
  driver.step(2.0 * ulp / kCreepDt);
  CHECK(driver.entity.lane.s > s_before);
  CHECK(driver.entity.lane.s - s_before == Approx(2.0 * ulp).margin(ulp));
}
