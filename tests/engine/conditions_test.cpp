// Conditions: one fixture per family (tests/engine/fixtures/condition_*.xosc). Each condition
// starts a marker event; the tests check when it started.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "engine_fixture.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"
#include "temp_dir.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::TransitionKind;

std::optional<double> started(const FixtureRun& run, const std::string& event) {
  return run.first("Marks::M::" + event, TransitionKind::kStart);
}

// Writes fixture `name` into `dir` with each (from, to) of `replacements` made once.
void copy_fixture(const corsa::test::TempDir& dir, const std::string& name,
                  const std::vector<std::pair<std::string, std::string>>& replacements = {}) {
  std::ostringstream read;
  read << std::ifstream(engine_fixture(name), std::ios::binary).rdbuf();
  std::string text = read.str();
  for (const auto& [from, to] : replacements) {
    REQUIRE(text.find(from) != std::string::npos);
    text.replace(text.find(from), from.size(), to);
  }
  std::ofstream(dir.path() / name, std::ios::binary) << text;
}

TEST_CASE("SimulationTimeCondition compares the time on the tick grid with each rule",
          "[engine][condition][time]") {
  FixtureRun run(engine_fixture("condition_simulation_time.xosc"));
  run.run();
  CHECK(started(run, "BeforeHalf") == Approx(0.0));
  CHECK(started(run, "AfterOne") == Approx(1.01));
  CHECK(started(run, "AtTwo") == Approx(2.0));
  CHECK(started(run, "EqualThree") == Approx(3.0));
}

TEST_CASE("Speed, relative speed, acceleration, traveled distance and stand-still conditions",
          "[engine][condition][motion]") {
  FixtureRun run(engine_fixture("condition_motion.xosc"));
  run.run();
  // Acc speeds up at 2 m/s^2 from 0 (Init), brakes sinusoidally from 12.01 s to 14.01 s.
  CHECK(started(run, "Faster10") == Approx(5.01));     // speed > 10 m/s
  CHECK(started(run, "LateralStill") == Approx(0.0));  // lateral speed 0
  CHECK(started(run, "PassesConst") == Approx(6.01));  // faster than Const's 12 m/s
  CHECK(started(run, "Accelerating") == Approx(0.01));
  const auto braking = started(run, "Braking");
  REQUIRE(braking);
  CHECK(*braking > 12.01);
  CHECK(*braking < 12.5);
  CHECK(run.at(*braking, "Acc").acceleration < -3.0);
  CHECK(started(run, "Hundred") == Approx(10.0));  // 100 m driven: t^2 = 100
  CHECK(run.at(14.01, "Acc").speed == 0.0);
  CHECK(started(run, "Stopped") == Approx(15.01));  // still for one second
}

TEST_CASE("A StandStillCondition in a stop trigger alone keeps the stand-still timer",
          "[engine][condition][motion]") {
  // The timers are kept only when a trigger of the storyboard reads them. Here the one
  // StandStillCondition is in the Storyboard's or the Act's StopTrigger (the event's is made a
  // SpeedCondition that never holds): Acc stands from 14.01 s, so either stops at 15.01 s.
  const std::string still = "<StandStillCondition duration=\"1\"/>";
  const std::string by_still =
      "<ByEntityCondition><TriggeringEntities triggeringEntitiesRule=\"any\"><EntityRef "
      "entityRef=\"Acc\"/></TriggeringEntities><EntityCondition>" +
      still + "</EntityCondition></ByEntityCondition>";
  const std::string never = "<SpeedCondition value=\"100\" rule=\"greaterThan\"/>";
  const std::string end_at_16 =
      "<ByValueCondition><SimulationTimeCondition value=\"16\" rule=\"greaterThan\"/>"
      "</ByValueCondition>";
  corsa::test::TempDir dir;
  copy_fixture(dir, "straight.xodr");
  engine::SimulationOptions options;
  options.duration = 20.0;
  SECTION("the Storyboard's StopTrigger") {
    copy_fixture(dir, "condition_motion.xosc", {{still, never}, {end_at_16, by_still}});
    FixtureRun run(dir.path() / "condition_motion.xosc", options);
    run.run();
    CHECK_FALSE(started(run, "Stopped"));
    CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
    CHECK(static_cast<double>(run.sim().tick()) * run.sim().dt() == Approx(15.01));
  }
  SECTION("an Act's StopTrigger") {
    const std::string act_end = "</ManeuverGroup></Act>";
    const std::string act_stop =
        "</ManeuverGroup><StopTrigger><ConditionGroup><Condition "
        "name=\"halt\" delay=\"0\" conditionEdge=\"none\">" +
        by_still + "</Condition></ConditionGroup></StopTrigger></Act>";
    copy_fixture(dir, "condition_motion.xosc", {{still, never}, {act_end, act_stop}});
    FixtureRun run(dir.path() / "condition_motion.xosc", options);
    run.run();
    CHECK_FALSE(started(run, "Stopped"));
    CHECK(run.first("S::A", TransitionKind::kStop) == Approx(15.01));
  }
}

TEST_CASE("TraveledDistanceCondition sums straight distances between steps, jumps left out",
          "[engine][condition][motion]") {
  // Corner drives lane -1 of a left arc, its centre on radius 11.75 m, at 10 m/s: 1 m along the
  // lane per 0.1 s step, 0.999925 m in a straight line. 5 m along the lane at 0.5 s, 4.99962 m
  // of straight steps: the 5 m condition holds from 0.6 s (esmini's odometer). Jumper stands
  // and is teleported 10 m along its lane at 1 s: its 1 m condition never holds.
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("condition_traveled_straight.xosc"), options);
  run.run();
  CHECK(run.at(0.5, "Corner").odometer == Approx(5.0).margin(1e-9));  // along the lane
  CHECK(run.at(0.5, "Corner").road->s == Approx(5.0 * 10.0 / 11.75).margin(1e-6));
  CHECK(started(run, "CornerFive") == Approx(0.6));
  CHECK_FALSE(started(run, "JumperOne"));
  CHECK(run.at(1.1, "Jumper").road->s == Approx(50.0).margin(1e-9));
}

TEST_CASE("Distance conditions between reference points, free space and boxes",
          "[engine][condition][distance]") {
  FixtureRun run(engine_fixture("condition_distances.xosc"));
  run.run();
  // Runner (20 m/s, rear axle at s = 0) follows Slow (10 m/s, 120 m ahead); both boxes reach
  // 3.65 m ahead of and 0.85 m behind their reference points.
  CHECK(started(run, "Reached") == Approx(4.95));     // within 1 m of s = 100
  CHECK(started(run, "Near") == Approx(7.51));        // reference point within 50 m of x = 200
  CHECK(started(run, "NearFree") == Approx(7.32));    // front of the box within 50 m
  CHECK(started(run, "Headway") == Approx(8.01));     // (120 - 10 t) / 20 < 2 s
  CHECK(started(run, "Imminent") == Approx(8.56));    // (115.5 - 10 t) / 10 < 3 s
  CHECK(started(run, "Close") == Approx(9.56));       // bumper to bumper < 20 m
  CHECK(started(run, "CloseRoad") == Approx(9.56));   // the same in road coordinates
  CHECK(started(run, "Crash") == Approx(11.55));      // boxes touch
  CHECK(started(run, "CrashType") == Approx(11.55));  // Slow hit by a vehicle
  REQUIRE(!run.sim().collisions().empty());
  CHECK(run.sim().collisions().front().time == Approx(11.55));
  CHECK(run.sim().colliding(run.entity("Runner"), run.entity("Slow")));
}

TEST_CASE("A distance's inputs change with every bit the distance reads and with nothing else",
          "[engine][condition][distance]") {
  // RelativeDistanceCondition and LongitudinalDistanceAction measure again only when
  // EntityDistanceInputs::same_as fails: it must fail for any change entity_distance can see.
  using engine::detail::Entity;
  // Entities are not copied (they own their light settings): each case sets a pair up afresh.
  // Their boxes are fixed once they exist (Entity::info): no change of one is to be seen.
  const auto set_up = [](Entity& from, Entity& to) {
    for (Entity* e : {&from, &to}) {
      e->write_state().pose = {1.0, 2.0, 0.0, 0.5, 0.0, 0.0};
      e->write_state().road = engine::RoadCoordinates{3, 0, -1, 10.0, -1.75};
      e->lane.on_road = true;
      e->lane.dir = 1;
    }
    to.write_state().pose.x = 30.0;
  };
  Entity from, to;
  set_up(from, to);
  engine::detail::EntityDistanceInputs inputs;
  CHECK(!inputs.same_as(from, to));  // nothing taken yet
  inputs.take(from, to);
  CHECK(inputs.same_as(from, to));
  // What the distance does not read: speeds, odometers.
  from.write_state().speed = 12.0;
  from.write_state().odometer = 3.0;
  to.write_state().speed = 4.0;
  CHECK(inputs.same_as(from, to));
  const auto changed = [&](auto change) {
    Entity a, b;
    set_up(a, b);
    change(a, b);
    return !inputs.same_as(a, b);
  };
  CHECK(!changed([](Entity&, Entity&) {}));
  CHECK(changed([](Entity&, Entity& b) { b.write_state().pose.x = std::nextafter(30.0, 31.0); }));
  CHECK(changed([](Entity& a, Entity&) { a.write_state().pose.h = std::nextafter(0.5, 1.0); }));
  CHECK(changed([](Entity& a, Entity&) { a.write_state().pose.z = -0.0; }));  // -0 is not +0
  CHECK(changed([](Entity&, Entity& b) { b.write_state().pose.r = 1e-300; }));
  CHECK(changed([](Entity& a, Entity&) { a.write_state().road->s = 10.5; }));
  CHECK(changed([](Entity&, Entity& b) { b.write_state().road->t = -1.5; }));
  CHECK(changed([](Entity&, Entity& b) { b.write_state().road->road = 4; }));
  CHECK(changed([](Entity&, Entity& b) { b.write_state().road.reset(); }));
  CHECK(changed([](Entity& a, Entity&) { a.lane.dir = -1; }));
  CHECK(changed([](Entity& a, Entity&) { a.lane.on_road = false; }));
  // The same arguments in the other order are other inputs.
  CHECK(!inputs.same_as(to, from));
}

TEST_CASE("A distance's inputs pass over states whose counts of writes stand, and no other input",
          "[engine][condition][distance]") {
  // EntityDistanceInputs is asked about one pair: while neither entity's count of its state's
  // writes has moved, the poses and road coordinates are the ones taken; the lane direction is
  // compared all the same.
  using engine::detail::Entity;
  Entity from, to;
  for (Entity* e : {&from, &to}) {
    e->write_state().pose = {1.0, 2.0, 0.0, 0.5, 0.0, 0.0};
    e->lane.on_road = true;
    e->lane.dir = 1;
  }
  engine::detail::EntityDistanceInputs inputs;
  inputs.take(from, to);
  CHECK(inputs.same_as(from, to));
  // Counts standing, other inputs changed: measured again.
  from.lane.dir = -1;
  CHECK_FALSE(inputs.same_as(from, to));
  from.lane.dir = 1;
  from.lane.on_road = false;
  CHECK_FALSE(inputs.same_as(from, to));
  from.lane.on_road = true;
  CHECK(inputs.same_as(from, to));
  // A write that changes nothing moves the count: the state is compared, and is the same.
  const uint32_t count = to.state_changes();
  to.write_state().pose.x = 1.0;
  CHECK(to.state_changes() != count);
  CHECK(inputs.same_as(from, to));
  to.write_state().pose.y = std::nextafter(2.0, 3.0);
  CHECK_FALSE(inputs.same_as(from, to));
  inputs.take(from, to);
  CHECK(inputs.same_as(from, to));
}

TEST_CASE("a lane of type none is off the road", "[engine][condition][road]") {
  // OpenDRIVE 1.8 §9.5.3: a lane of type none is the space where a driver has left the road.
  // The fixture's Drifter steps 3.5 m right of lane -3, into lane -4, made of type none here.
  corsa::test::TempDir dir;
  copy_fixture(dir, "straight.xodr",
               {{"<lane id=\"-4\" type=\"sidewalk\"", "<lane id=\"-4\" type=\"none\""}});
  copy_fixture(
      dir, "condition_road.xosc",
      {{"<AbsoluteTargetLaneOffset value=\"-6\"/>", "<AbsoluteTargetLaneOffset value=\"-3.5\"/>"}});
  FixtureRun run(dir.path() / "condition_road.xosc");
  run.run();
  REQUIRE(run.at(1.02, "Drifter").road.has_value());
  CHECK(run.at(1.02, "Drifter").road->lane == -4);
  CHECK(started(run, "OffRoad") == Approx(1.52));
}

TEST_CASE("End-of-road, off-road and relative clearance conditions", "[engine][condition][road]") {
  FixtureRun run(engine_fixture("condition_road.xosc"));
  run.run();
  // Ender reaches the road's end (s = 1000) at 5 s and stops there: 0.5 s later it holds.
  CHECK(started(run, "AtEnd") == Approx(5.5));
  CHECK(run.now("Ender").speed == 0.0);
  CHECK(run.now("Ender").road->s == Approx(1000.0));
  // Drifter steps 6 m right of lane -3 at 1.01 s, off every lane from the next tick.
  CHECK(run.at(1.0, "Drifter").road.has_value());
  CHECK(!run.at(1.02, "Drifter").road.has_value());
  CHECK(started(run, "OffRoad") == Approx(1.52));
  // Passer, in the lane left of Ego, is within 20 m of it from 2 s to 6 s.
  const auto clear = started(run, "Clear");
  REQUIRE(clear);
  CHECK(*clear == Approx(6.0).margin(0.011));
}

TEST_CASE("Triggering entities: any, all, and the entities that fired as actors",
          "[engine][condition][triggering]") {
  FixtureRun run(engine_fixture("condition_triggering_entities.xosc"));
  run.run();
  CHECK(started(run, "AnyHundred") == Approx(3.34));  // C at 30 m/s first
  CHECK(started(run, "AllHundred") == Approx(10.0));  // A at 10 m/s last
  // B passed 150 m first (at 7.5 s): only B is slowed down.
  CHECK(run.first("Chosen::M::SlowFast", TransitionKind::kStart) == Approx(7.5));
  CHECK(run.now("B").speed == 5.0);
  CHECK(run.now("A").speed == 10.0);
  CHECK(run.now("C").speed == 30.0);
}

TEST_CASE("A ReachPositionCondition on a standing entity holds on the step its pose does",
          "[engine][condition][reach]") {
  // A pose that changes after standing (a teleport of a standing entity, a drive off) is read on
  // the step it changes, and a position relative to another entity as that entity moves, while
  // the triggering entity stands. (A skip of conditions whose inputs stand must keep these.)
  FixtureRun run(engine_fixture("condition_reach_standing.xosc"));
  run.run();
  const auto start = [&](const std::string& event) {
    return run.first(event, TransitionKind::kStart);
  };
  // Stander stands at s = 10 for 1 s; the teleport to s = 50 meets the condition on s = 50 and
  // ends the one on s = 10 (a falling edge) in the same step.
  CHECK(start("JumperM::Jump") == Approx(1.01));
  CHECK(start("JumperM::Reached50") == Approx(1.01));
  CHECK(start("JumperM::LeftStart") == Approx(1.01));
  CHECK(run.count("JumperM::Never", TransitionKind::kStart) == 0);
  // Walker stands at s = 10 for 2 s, then drives at 10 m/s: within 0.5 m of s = 40 at 4.96 s.
  CHECK(start("DriverM::Go") == Approx(2.01));
  CHECK(start("DriverM::Reached40") == Approx(4.96));
  // Post stands at s = 30 all along; the position it waits for, Walker's, is within 1 m of it
  // from 3.91 s.
  CHECK(start("WatcherM::Caught") == Approx(3.91));
  CHECK(run.now("Post").pose.x == Approx(30.0).margin(1e-9));
}

TEST_CASE("ReachPositionConditions of one definition share their values, not their edges",
          "[engine][condition][reach]") {
  // Walker drives at 10 m/s from s = 10; the conditions on s = 40 with a tolerance of 0.5 m share
  // one memo of their value (one definition), each with its own edge, delay and entity: the
  // shared value must change as Walker comes and goes, and must not pass from one entity to
  // another.
  FixtureRun run(engine_fixture("condition_reach_shared.xosc"));
  run.run();
  const auto start = [&](const std::string& event) {
    return run.first(event, TransitionKind::kStart);
  };
  const auto reached = start("WalkerM::Reached");
  REQUIRE(reached);
  CHECK(*reached == Approx(2.95));
  CHECK(start("StanderM::WalkerThere") == reached);
  // The delay and the falling edge are the condition's own.
  CHECK(start("WalkerM::ReachedLater") == Approx(*reached + 1.0));
  CHECK(start("WalkerM::Left") == Approx(3.05));
  // Stander, 30 m away, never reaches s = 40, though its conditions read the memo right after
  // Walker's made it true.
  CHECK(run.count("WalkerM::StanderReached", TransitionKind::kStart) == 0);
  CHECK(run.count("StanderM::StanderThere", TransitionKind::kStart) == 0);
  CHECK(run.now("Stander").speed == 0.0);
  // Another tolerance is another definition: 2 m from s = 40 earlier.
  CHECK(start("StanderM::WalkerNear") == Approx(2.8));
  // s = 50, twice.
  CHECK(start("WatcherM::Passed") == Approx(3.95));
  CHECK(start("WatcherM::PassedToo") == start("WatcherM::Passed"));
}

}  // namespace
}  // namespace corsa::test
