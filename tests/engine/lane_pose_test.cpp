// The default controller's lane pose (lanes/lane_follow.h, lane_pose_of) evaluates the lanes
// only out to the followed one when the point is strictly inside it. It must give the bits of
// lane_pose, which evaluates every lane of the section, everywhere: on every lane of the shared
// maps, at lateral offsets inside, on and beyond the lane's borders, and on a road whose lanes
// overlap through <border> records.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../xodr/xodr_test_util.h"
#include "controllers/controllers.h"
#include "controllers/esmini_vehicle.h"
#include "corsa/xodr/map_parts.h"
#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "motion/controller.h"
#include "motion/pose_command.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace {

using corsa::engine::detail::LaneFollow;
using corsa::engine::detail::LanePose;
using corsa::xodr::LaneSpan;
using corsa::xodr::Map;

using corsa::engine::detail::same_bits;

bool same_pose(const LanePose& a, const LanePose& b) {
  return same_bits(a.t, b.t) && a.lane_at == b.lane_at && same_bits(a.pose.x, b.pose.x) &&
         same_bits(a.pose.y, b.pose.y) && same_bits(a.pose.z, b.pose.z) &&
         same_bits(a.pose.h, b.pose.h) && same_bits(a.pose.p, b.pose.p) &&
         same_bits(a.pose.r, b.pose.r);
}

struct Comparison {
  size_t poses = 0;
  size_t inside = 0;  ///< poses strictly inside the followed lane
  size_t mismatches = 0;
  std::string first_mismatch;
};

// Every lane of every section at five s, each at lateral offsets from its centre to beyond its
// borders (and exactly on them), in both directions of travel.
void compare_everywhere(const Map& map, const std::string& name, Comparison& out) {
  std::vector<LaneSpan> spans, scratch;
  for (uint32_t road = 0; road < map.road_count(); ++road) {
    const auto& sections = map.road(road).lane_sections;
    for (uint32_t section = 0; section < sections.size(); ++section) {
      const double start = sections[section].s;
      const double end = map.section_end(road, section);
      for (int k = 0; k <= 4; ++k) {
        const double s = start + (end - start) * k / 4.0;
        map.lane_spans_in_section(road, section, s, spans);
        for (const LaneSpan& span : std::vector<LaneSpan>(spans)) {
          const double half = 0.5 * span.width();
          for (const double lateral :
               {0.0, 0.3 * half, -0.9 * half, half, -half, 1.5 * half, 4.0}) {
            for (const int dir : {1, -1}) {
              LaneFollow follow;
              follow.on_road = true;
              follow.road = road;
              follow.section = section;
              follow.lane = span.id;
              follow.s = s;
              follow.dir = dir;
              follow.lateral = lateral;
              follow.heading_offset = 0.01;
              const LanePose all = corsa::engine::detail::lane_pose(map, follow, spans);
              const LanePose near = corsa::engine::detail::lane_pose_of(map, follow, scratch);
              ++out.poses;
              out.inside += all.lane_at == span.id && span.width() > 0.0 && all.t > span.t_min() &&
                            all.t < span.t_max();
              if (!same_pose(all, near) && out.mismatches++ == 0) {
                out.first_mismatch = name + " road " + map.road(road).id + " section " +
                                     std::to_string(section) + " lane " + std::to_string(span.id) +
                                     " s " + std::to_string(s);
              }
            }
          }
        }
      }
    }
  }
}

}  // namespace

TEST_CASE("The lane pose from the followed lane alone equals the one from every lane's span",
          "[engine][lanes]") {
  Comparison result;
  for (const auto& path : corsa::xodr::test::all_shared_maps()) {
    const Map map = corsa::xodr::test::load_map(path);
    compare_everywhere(map, path.filename().string(), result);
  }
  INFO(result.first_mismatch);
  CHECK(result.mismatches == 0);
  CHECK(result.inside > result.poses / 4);  // the shortcut is taken, not only the fallback
}

TEST_CASE("Lanes that overlap through border records give the lane pose of every lane's span",
          "[engine][lanes]") {
  corsa::xodr::MapData data;
  data.roads.push_back(
      corsa::xodr::test::make_road("1", corsa::xodr::LineGeometry{}, 100.0, 2, 3.0));
  // Lane 2's outer border comes back inside lane 1 (t = 2 m), so a point in lane 1 near its
  // outer border is also in lane 2; -2's border crosses -1 likewise. The inner lane must win.
  auto& lanes = data.roads[0].lane_sections[0].lanes;
  for (auto& lane : lanes) {
    if (lane.id == 2 || lane.id == -2) {
      lane.widths.clear();
      lane.borders.push_back(corsa::xodr::Poly3{0.0, lane.id > 0 ? 2.0 : -2.0, 0.0, 0.0, 0.0});
    }
  }
  corsa::Diagnostics diagnostics;
  const Map map = Map::build(std::move(data), diagnostics);
  Comparison result;
  compare_everywhere(map, "overlapping borders", result);
  INFO(result.first_mismatch);
  CHECK(result.mismatches == 0);
  CHECK(result.poses > 0);
}

namespace {

bool same_located(const std::optional<corsa::xodr::LanePosition>& a,
                  const std::optional<corsa::xodr::LanePosition>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->road == b->road && a->section == b->section && a->lane == b->lane &&
         same_bits(a->s, b->s) && same_bits(a->t, b->t) && same_bits(a->distance, b->distance) &&
         same_bits(a->heading, b->heading);
}

}  // namespace

TEST_CASE("An entity's remembered lane at a point is the map's answer, asked again elsewhere",
          "[engine][lanes]") {
  const Map map = corsa::xodr::test::load_map(corsa::xodr::test::all_shared_maps().front());
  corsa::xodr::LocateOptions options;
  options.max_distance = 0.5;
  corsa::engine::detail::Entity entity;
  std::vector<LaneSpan> spans;
  size_t asked = 0, found = 0, mismatches = 0;
  // Points on lanes, beside them and far off every road, each asked twice in a row (the memo
  // answers the second) and then after another point (the memo must ask the map again).
  std::vector<std::pair<double, double>> points;
  for (uint32_t road = 0; road < map.road_count(); ++road) {
    for (const double s : {0.0, 0.5 * map.road(road).length}) {
      for (const double t : {0.0, 1.7, -2.9, 6.3}) {
        const corsa::xodr::WorldPose at = map.world_pose(road, s, t);
        points.emplace_back(at.x, at.y);
      }
    }
  }
  points.emplace_back(1.0e6, -1.0e6);
  for (size_t i = 0; i < points.size(); ++i) {
    for (const auto& [x, y] : {points[i], points[i], points[(i + 7) % points.size()], points[i]}) {
      const auto expected = map.locate(x, y, options);
      const auto& got = corsa::engine::detail::locate_near(entity, map, x, y);
      ++asked;
      found += expected.has_value();
      mismatches += !same_located(expected, got);
    }
  }
  CHECK(mismatches == 0);
  CHECK(found > 0);
  CHECK(found < asked);  // points off the roads too
}

namespace {

bool same_surface(const corsa::xodr::SurfacePose* a,
                  const std::optional<corsa::xodr::SurfacePose>& b) {
  if (a == nullptr || !b) return a == nullptr && !b;
  return same_bits(a->z, b->z) && same_bits(a->p, b->p) && same_bits(a->r, b->r);
}

}  // namespace

// The road surface kept with the remembered lane at a point (surface_near) must be the one read
// from the map's answer afresh, on every shared map: at points on lanes, beside them and off
// every road, each asked twice in a row (the memo answers the second), then after another point
// (on another road or none: the memo must read the surface again), then within a smaller
// distance of the lane (the same answer, which may now lie too far).
TEST_CASE("The road surface kept with the remembered lane is the map's, read again elsewhere",
          "[engine][lanes][memo]") {
  corsa::xodr::LocateOptions options;
  options.max_distance = 0.5;
  size_t asked = 0, on_road = 0, mismatches = 0, refreshed = 0, climbed = 0;
  for (const auto& path : corsa::xodr::test::all_shared_maps()) {
    const Map map = corsa::xodr::test::load_map(path);
    corsa::engine::detail::Entity entity;  // the memo holds for one map
    std::vector<std::pair<double, double>> points;
    for (uint32_t road = 0; road < map.road_count(); ++road) {
      for (const double s : {0.0, 0.5 * map.road(road).length}) {
        for (const double t : {0.0, 1.7, -2.9, 6.3}) {
          const corsa::xodr::WorldPose at = map.world_pose(road, s, t);
          points.emplace_back(at.x, at.y);
        }
      }
    }
    points.emplace_back(1.0e6, -1.0e6);
    corsa::xodr::SurfacePose last;
    bool have_last = false;
    for (size_t i = 0; i < points.size(); ++i) {
      const auto& other = points[(i + 7) % points.size()];
      for (const auto& [x, y, within] : {std::tuple{points[i].first, points[i].second, 0.5},
                                         std::tuple{points[i].first, points[i].second, 0.5},
                                         std::tuple{other.first, other.second, 0.5},
                                         std::tuple{points[i].first, points[i].second, 0.2}}) {
        const auto at = corsa::engine::detail::road_point_within(map.locate(x, y, options), within);
        std::optional<corsa::xodr::SurfacePose> expected;
        if (at) expected = corsa::xodr::surface_pose(map, at->road, at->s, at->t);
        const corsa::xodr::SurfacePose* got =
            corsa::engine::detail::surface_near(entity, map, x, y, within);
        ++asked;
        on_road += expected.has_value();
        mismatches += !same_surface(got, expected);
        // Where the last answer differs, a memo not read again would show it.
        refreshed += !same_surface(have_last ? &last : nullptr, expected);
        climbed += have_last && expected && !same_bits(last.z, expected->z);
        have_last = got != nullptr;
        if (got != nullptr) last = *got;
      }
    }
  }
  CHECK(mismatches == 0);
  CHECK(on_road > 0);
  CHECK(on_road < asked);  // points off the roads too
  CHECK(refreshed > asked / 4);
  CHECK(climbed > 0);  // heights differ between points: some maps are not flat
}

TEST_CASE("The curvature memo reads a road and s once, and again for other bits of either",
          "[engine][motion][memo]") {
  corsa::engine::detail::CurvatureMemo memo;
  int reads = 0;
  const auto read = [&](double value) {
    return [&reads, value] {
      ++reads;
      return value;
    };
  };
  CHECK(memo.at(3, 12.5, read(0.25)) == 0.25);
  CHECK(memo.at(3, 12.5, read(9.0)) == 0.25);  // the same pair: not read again
  CHECK(reads == 1);
  CHECK(memo.at(4, 12.5, read(0.5)) == 0.5);                          // another road
  CHECK(memo.at(3, std::nextafter(12.5, 13.0), read(0.75)) == 0.75);  // another s by one ulp
  CHECK(memo.at(3, 0.0, read(1.0)) == 1.0);
  CHECK(memo.at(3, -0.0, read(2.0)) == 2.0);  // -0 and +0 differ in their bits
  CHECK(reads == 5);
  // Many pairs share the slots: whatever was evicted, each answer is its own pair's.
  for (int i = 0; i < 200; ++i) {
    const double s = 0.1 * i;
    CHECK(memo.at(static_cast<uint32_t>(i % 7), s, read(s * 2.0 + i % 7)) == s * 2.0 + i % 7);
  }
  for (int i = 0; i < 200; ++i) {
    const double s = 0.1 * i;
    CHECK(memo.at(static_cast<uint32_t>(i % 7), s, read(s * 2.0 + i % 7)) == s * 2.0 + i % 7);
  }
}

TEST_CASE("A pose command to where an entity off the road stands is kept without the map",
          "[engine][lanes]") {
  using corsa::engine::detail::Entity;
  const Map map = corsa::xodr::test::load_map(corsa::xodr::test::all_shared_maps().front());
  std::vector<LaneSpan> spans;
  const corsa::engine::detail::MotionContext context{&map, 0.05, &spans};
  // Far off every road: the memo answers nothing there, with a clearance around the point.
  const double x = 1.0e6, y = -1.0e6, h = 0.3;
  // An entity standing there, its memo asked for the point (Entity holds move-only parts).
  const auto standing = [&] {
    Entity entity;
    entity.write_state().placed = true;
    entity.write_state().pose = {x, y, 1.5, h, 0.02, 0.0};
    entity.write_state().speed = 2.0;
    entity.write_state().lateral_speed = 0.2;
    entity.write_state().odometer = 10.0;
    entity.write_state().road = corsa::engine::RoadCoordinates{1, 0, -1, 3.0, -1.0};
    entity.speed_command = 1.5;
    entity.lateral_command = 0.7;
    entity.end_of_road = true;
    REQUIRE_FALSE(corsa::engine::detail::locate_near(entity, map, x, y).has_value());
    return entity;
  };
  const Entity entity = standing();
  // Held: the writes of a pose command to the same pose.
  Entity held = standing();
  REQUIRE(corsa::engine::detail::keeps_pose_off_lanes(held, x, y, h, context));
  corsa::engine::detail::hold_pose_off_lanes(held, context);
  Entity moved = standing();
  moved.pose_command = moved.state().pose;
  corsa::engine::detail::move_to_pose_command(moved, context);
  CHECK(same_bits(static_cast<const corsa::engine::detail::EntityMotion&>(held),
                  static_cast<const corsa::engine::detail::EntityMotion&>(moved)));
  CHECK_FALSE(held.pose_command.has_value());
  CHECK_FALSE(held.state().road.has_value());
  CHECK(held.state().speed == 1.5);
  CHECK(held.state().yaw_rate == 0.0);
  // Held again at the speed it has (its acceleration turns 0), then once more: that hold changes
  // nothing of the state and leaves it unwritten, its count of writes standing; a new speed is
  // written. Each hold leaves what the pose command would.
  const auto hold_both = [&] {
    corsa::engine::detail::hold_pose_off_lanes(held, context);
    moved.pose_command = moved.state().pose;
    corsa::engine::detail::move_to_pose_command(moved, context);
    CHECK(same_bits(static_cast<const corsa::engine::detail::EntityMotion&>(held),
                    static_cast<const corsa::engine::detail::EntityMotion&>(moved)));
  };
  hold_both();
  CHECK(held.state().acceleration == 0.0);
  const uint32_t count = held.state_changes();
  hold_both();
  CHECK(held.state_changes() == count);
  held.speed_command = 1.25;
  moved.speed_command = 1.25;
  hold_both();
  CHECK(held.state_changes() != count);
  CHECK(held.state().speed == 1.25);
  // Not held: another point, another heading, -0 for +0, a NaN, an entity whose memo holds a
  // lane, and no map.
  CHECK_FALSE(
      corsa::engine::detail::keeps_pose_off_lanes(entity, std::nextafter(x, 0.0), y, h, context));
  CHECK_FALSE(corsa::engine::detail::keeps_pose_off_lanes(entity, x, y, h + 1e-12, context));
  Entity at_zero = standing();
  at_zero.write_state().pose.h = 0.0;
  CHECK_FALSE(corsa::engine::detail::keeps_pose_off_lanes(at_zero, x, y, -0.0, context));
  Entity not_a_number = standing();
  not_a_number.write_state().pose.x = std::nan("");
  CHECK_FALSE(
      corsa::engine::detail::keeps_pose_off_lanes(not_a_number, std::nan(""), y, h, context));
  const corsa::xodr::WorldPose on_lane = map.world_pose(0, 0.5 * map.road(0).length, 0.0);
  Entity on_road = standing();
  on_road.write_state().pose.x = on_lane.x;
  on_road.write_state().pose.y = on_lane.y;
  REQUIRE(corsa::engine::detail::locate_near(on_road, map, on_lane.x, on_lane.y).has_value());
  CHECK_FALSE(
      corsa::engine::detail::keeps_pose_off_lanes(on_road, on_lane.x, on_lane.y, h, context));
  const corsa::engine::detail::MotionContext no_map{nullptr, 0.05, &spans};
  CHECK_FALSE(corsa::engine::detail::keeps_pose_off_lanes(entity, x, y, h, no_map));
}

// A vehicle model at rest on its lane (esmini's, whose speed only nears 0) is held where it
// stands without the map (keeps_pose_on_lane, hold_pose_on_lane). Every step must leave what the
// pose command to the model's pose leaves: while it stands for many steps, after a teleport puts
// it elsewhere (its point memo then holds another point), and once its model moves it again.
TEST_CASE("A model standing on its lane is placed as by its pose command, and after it moves",
          "[engine][lanes]") {
  using corsa::engine::detail::Entity;
  using corsa::engine::detail::EntityMotion;
  const Map map = corsa::xodr::test::load_map(corsa::xodr::test::all_shared_maps().front());
  std::vector<LaneSpan> spans;
  const corsa::engine::detail::MotionContext context{&map, 0.05, &spans};
  // The centre of road 0's first right-hand lane halfway along, and a point 2 m along it.
  const double s = 0.5 * map.road(0).length;
  corsa::xodr::WorldPose here = map.world_pose(0, s, -1.5);
  corsa::xodr::WorldPose ahead = map.world_pose(0, s + 2.0, -1.5);
  here.h = corsa::engine::detail::remainder_full_turn(here.h);  // the model's headings
  ahead.h = corsa::engine::detail::remainder_full_turn(ahead.h);
  const auto placed = [&] {
    Entity entity;
    entity.write_state().placed = true;
    entity.write_state().pose = {here.x + 1.0, here.y, 0.0, here.h, 0.0, 0.0};
    entity.speed_command = 3.0;
    return entity;
  };
  // Placed by the pose command, as the model's placement does away from a standstill.
  const auto by_command = [&](Entity& entity, double x, double y, double h, double speed) {
    auto pose = entity.state().pose;
    pose.x = x;
    pose.y = y;
    pose.h = h;
    if (const auto* surface = corsa::engine::detail::surface_near(entity, map, x, y, 0.5)) {
      pose.z = surface->z;
      pose.p = surface->p;
    }
    entity.pose_command = pose;
    corsa::engine::detail::move_at_controller_speed(
        entity, speed, [&] { corsa::engine::detail::move_to_pose_command(entity, context); });
  };
  Entity model = placed();
  Entity command = placed();
  size_t held = 0;
  const auto step = [&](double x, double y, double h, double speed) {
    held += corsa::engine::detail::keeps_pose_on_lane(model, x, y, h, 0.5, context);
    corsa::engine::detail::place_entity_at_model(x, y, h, speed, model, context);
    by_command(command, x, y, h, speed);
    CHECK(same_bits(static_cast<const EntityMotion&>(model),
                    static_cast<const EntityMotion&>(command)));
    CHECK(model.speed_command == command.speed_command);
    CHECK_FALSE(model.pose_command.has_value());
  };
  step(here.x, here.y, here.h, 2.0);  // onto the lane
  REQUIRE(model.lane.on_road);
  double speed = 2.0;
  for (int i = 0; i < 500; ++i) {
    speed *= 0.999;  // the engine brake: the speed changes, the pose does not
    step(here.x, here.y, here.h, speed);
  }
  CHECK(held == 500);
  CHECK(model.state().speed == speed);
  CHECK(model.state().odometer == command.state().odometer);
  // A teleport to the point ahead: the memo holds the point it stood at, and the map is asked.
  for (Entity* entity : {&model, &command}) {
    entity->write_state().pose = {ahead.x, ahead.y, 0.0, ahead.h, 0.0, 0.0};
  }
  CHECK_FALSE(
      corsa::engine::detail::keeps_pose_on_lane(model, ahead.x, ahead.y, ahead.h, 0.5, context));
  step(ahead.x, ahead.y, ahead.h, speed);
  CHECK(model.state().pose.z == command.state().pose.z);
  for (int i = 0; i < 20; ++i) step(ahead.x, ahead.y, ahead.h, speed);
  CHECK(held == 520);
  // Its model moves it back along the lane, and a turn by one ulp is a move too.
  step(here.x, here.y, here.h, 1.0);
  CHECK(model.state().odometer > 2.0);
  CHECK_FALSE(corsa::engine::detail::keeps_pose_on_lane(
      model, here.x, here.y, std::nextafter(here.h, 10.0), 0.5, context));
  step(here.x, here.y, std::nextafter(here.h, 10.0), 1.0);
  CHECK(held == 520);
  // Not held: no map, and an entity off its lane.
  const corsa::engine::detail::MotionContext no_map{nullptr, 0.05, &spans};
  CHECK_FALSE(corsa::engine::detail::keeps_pose_on_lane(
      model, model.state().pose.x, model.state().pose.y, model.state().pose.h, 0.5, no_map));
  model.lane.on_road = false;
  CHECK_FALSE(corsa::engine::detail::keeps_pose_on_lane(
      model, model.state().pose.x, model.state().pose.y, model.state().pose.h, 0.5, context));
}
