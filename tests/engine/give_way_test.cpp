// Generated traffic gives way in junctions (controllers/give_way.h) and walkers wait at the
// kerb for vehicles (controllers/npc_caution.h): generated cars put on the four-way
// intersection of scenarios/maps and moved by the engine's entity mover, step by step.

#include "controllers/give_way.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "controllers/controllers.h"
#include "controllers/follow_view.h"
#include "controllers/junction_conflicts.h"
#include "controllers/npc_caution.h"
#include "corsa/engine/oriented_box.h"
#include "corsa/xodr/parser.h"
#include "engine_fixture.h"
#include "state/sim_state.h"
#include "test_entity.h"
#include "traffic/spawner.h"

namespace corsa::test {
namespace {

// A placed entity at (x, y) with heading h (rad) and speed (m/s), appended to `state`.
void add_entity(engine::detail::SimState& state, double x, double y, double h, double speed,
                const engine::Box& box, engine::ObjectKind kind) {
  engine::detail::Entity entity = corsa::test::entity_of(box, kind);
  entity.write_state().placed = true;
  entity.write_state().pose.x = x;
  entity.write_state().pose.y = y;
  entity.write_state().pose.h = h;
  entity.write_state().speed = speed;
  state.world.entities.push_back(std::move(entity));
}

std::string intersection_text() {
  std::ifstream in(std::filesystem::path(CORSA_SOURCE_DIR) /
                   "scenarios/maps/intersection_4way.xodr");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Give-way signs (205) on the road with id `road`, facing the traffic toward the junction at its
// start (driving -s).
std::string with_give_way_sign(std::string text, const std::string& road) {
  const size_t at = text.find("<road name=\"Arm " + road + "\"");
  const size_t end = text.find("</road>", at);
  text.insert(end, "<signals><signal s=\"2\" t=\"5\" id=\"yield" + road +
                       "\" dynamic=\"no\" orientation=\"-\" country=\"DE\" type=\"205\" "
                       "subtype=\"-1\" zOffset=\"2\" height=\"0.8\" width=\"0.8\"/></signals>");
  return text;
}

std::shared_ptr<const xodr::Map> map_of(const std::string& text) {
  Diagnostics diagnostics;
  return std::make_shared<const xodr::Map>(xodr::Map::build(
      xodr::parse_xodr_text(text, "intersection_4way.xodr", diagnostics), diagnostics));
}

// The junction's <priority> elements: each `high` connecting road over each `low` one, pairwise.
std::string with_priorities(std::string text, const std::vector<std::string>& high,
                            const std::vector<std::string>& low) {
  std::string elements;
  for (size_t k = 0; k < high.size(); ++k) {
    elements += "<priority high=\"" + high[k] + "\" low=\"" + low[k] + "\"/>";
  }
  text.insert(text.find("</junction>"), elements);
  return text;
}

// The ids of the connecting roads whose lanes have right of way `right`.
std::set<std::string> roads_with(const xodr::Map& map,
                                 const engine::detail::JunctionConflicts& conflicts,
                                 engine::detail::RightOfWay right) {
  std::set<std::string> roads;
  for (uint32_t node = 0; node < map.lane_graph().size(); ++node) {
    if (conflicts.right_of_way(node) == right) {
      roads.insert(map.road(map.lane_graph().info(node).lane.road).id);
    }
  }
  return roads;
}

// Puts generated cars where a test wants them, named as `--npc` names its vehicles: NPC
// vehicles as `--npc` places them (`npc`: flagged as its generator flags them), or else as the
// objects of a traffic action would be. Kept in the traffic state, as `--npc`'s generator is.
class Placer final : public engine::detail::GeneratorBase, public engine::detail::NpcPlacement {
 public:
  Placer() : GeneratorBase(std::string("test"), "car", 1), cars_(prototype()) {}
  void step(engine::detail::SimState&) override {}
  uint32_t car(engine::detail::SimState& state, double x, double y, double speed, bool npc) {
    const auto at = engine::detail::lane_spot(*state.map, x, y, false);
    REQUIRE(at);
    const uint32_t i =
        spawn(state, cars_, 0, *at, speed, "npc_vehicle_" + std::to_string(placed_++));
    vehicle_flags_.resize(std::max<size_t>(vehicle_flags_.size(), i + 1), 0);
    vehicle_flags_[i] = npc ? 1 : 0;
    return i;
  }

 private:
  static xosc::ScenarioObject prototype() {
    xosc::ScenarioObject object;
    object.object = engine::detail::vehicle_model(xosc::VehicleCategory::kCar);
    return object;
  }
  engine::detail::TrafficMix cars_;
  uint32_t placed_ = 0;
};

// A run of generated cars on the intersection, moved by the entity mover.
struct Crossing {
  xosc::Scenario scenario;
  Diagnostics diagnostics;
  engine::detail::SimState state;
  Placer& placer;
  engine::detail::EntityMover mover{1};
  std::vector<double> least_speed;  ///< by car, over the run
  std::vector<double> most_gain;    ///< m/s^2 by car: the fastest it sped up in a step
  std::vector<double> hardest;      ///< m/s^2 by car: the hardest it braked in a step
  std::string overlaps;

  explicit Crossing(const std::string& map_text)
      : state(scenario, map_of(map_text), engine::SimulationOptions{}, diagnostics),
        placer(placed_by(state)) {}

  static Placer& placed_by(engine::detail::SimState& state) {
    auto placer = std::make_unique<Placer>();
    Placer& out = *placer;
    state.traffic.generators.push_back(std::move(placer));
    return out;
  }

  // The arms: 1 east, 2 north, 3 west, 4 south of the junction; cars on the lane toward it
  // (NPC vehicles unless `npc` is false).
  uint32_t car_on_arm(int arm, double distance, double speed, bool npc = true) {
    const double a = (arm - 1) * 0.5 * std::numbers::pi;
    const double along = 12.0 + distance, left = 1.75;
    const uint32_t i = placer.car(state, along * std::cos(a) - left * std::sin(a),
                                  along * std::sin(a) + left * std::cos(a), speed, npc);
    least_speed.resize(state.world.entities.size(), speed);
    most_gain.resize(state.world.entities.size(), 0.0);
    hardest.resize(state.world.entities.size(), 0.0);
    return i;
  }

  void run(double seconds) {
    engine::detail::MotionContext motion;
    motion.map = state.map;
    motion.dt = 0.01;
    const auto steps = static_cast<int>(std::lround(seconds / motion.dt));
    for (int k = 0; k < steps; ++k) {
      std::vector<double> before;
      for (const auto& entity : state.world.entities) {
        before.push_back(entity.state().speed);
      }
      mover.move(state, motion);
      ++state.tick;
      const auto& entities = state.world.entities;
      for (size_t a = 0; a < entities.size(); ++a) {
        const double change = (entities[a].state().speed - before[a]) / motion.dt;
        most_gain[a] = std::max(most_gain[a], change);
        hardest[a] = std::max(hardest[a], -change);
        least_speed[a] = std::min(least_speed[a], entities[a].state().speed);
        for (size_t b = a + 1; b < entities.size(); ++b) {
          const double gap =
              engine::box_distance(engine::box_of(entities[a].info.box, entities[a].state().pose),
                                   engine::box_of(entities[b].info.box, entities[b].state().pose));
          if (gap <= 0.0 && overlaps.size() < 400) {
            overlaps += std::to_string(state.now()) + " s: cars " + std::to_string(a) + " and " +
                        std::to_string(b) + "\n";
          }
        }
      }
    }
  }

  // Whether car `i` has left the junction on another arm than the one it came from.
  bool through(uint32_t i, int from_arm) const {
    const auto& road = state.world.entities[i].state().road;
    if (!road) {
      return false;
    }
    const xodr::Road& now = state.map->road(road->road);
    return !now.in_junction() && now.id != std::to_string(from_arm) && road->s > 5.0;
  }
};

// A vehicle's approach for the claims pass: at `speed`, its claims {conflict, side, m to enter,
// zone's lane} in path order, approaching since tick `arrived`; its maximum deceleration
// `hardest` (m/s^2, a generated car's by default).
engine::detail::Approach approach(double speed, int64_t arrived,
                                  const std::vector<engine::detail::Claim>& claims,
                                  double hardest = 8.0) {
  engine::detail::Approach a;
  a.stopping = speed * speed / (2.0 * engine::detail::kFirm);  // as GiveWay::record
  a.emergency = speed * speed / (2.0 * hardest);
  a.arrived = arrived;
  for (const auto& claim : claims) {
    a.claims[a.count++] = claim;
  }
  return a;
}

}  // namespace

TEST_CASE("The four-way intersection's paths conflict where they cross, not where they part",
          "[engine][npc][give_way]") {
  const auto map = map_of(intersection_text());
  const auto conflicts = engine::detail::JunctionConflicts::build(*map);
  // 12 connecting lanes, 3 from each arm (left, straight, right), which part at their start.
  CHECK(conflicts.conflict_count() > 12);
  CHECK(conflicts.conflict_count() < 12 * 11 / 2 - 4 * 3);
  for (uint32_t node = 0; node < map->lane_graph().size(); ++node) {
    const auto& info = map->lane_graph().info(node);
    if (!map->road(info.lane.road).in_junction()) {
      CHECK(conflicts.zones(node).empty());
    }
    CHECK(conflicts.right_of_way(node) == engine::detail::RightOfWay::kNormal);
  }
  // A give-way sign on arm 1 lowers the right of way of the lanes coming from it only.
  const auto signed_map = map_of(with_give_way_sign(intersection_text(), "1"));
  const auto signed_conflicts = engine::detail::JunctionConflicts::build(*signed_map);
  std::set<std::string> giving_way;
  for (uint32_t node = 0; node < signed_map->lane_graph().size(); ++node) {
    if (signed_conflicts.right_of_way(node) == engine::detail::RightOfWay::kGiveWay) {
      giving_way.insert(signed_map->road(signed_map->lane_graph().info(node).lane.road).id);
    }
  }
  // The connecting roads of the connections whose incoming road is road 1.
  CHECK(giving_way == std::set<std::string>{"101", "102", "103"});
}

TEST_CASE("A connecting lane's lane sections are not in conflict with each other",
          "[engine][npc][give_way]") {
  // Town04's ramps: connecting roads whose lane changes id between two lane sections (road
  // 1194: lane 6, then lane 2) merge into the main road's outer lane in the junction.
  Diagnostics diagnostics;
  const auto map = xodr::Map::load(
      std::filesystem::path(CORSA_SHARED_DIR) / "data/xodr/Town04.xodr", diagnostics);
  const auto conflicts = engine::detail::JunctionConflicts::build(map);
  const auto& graph = map.lane_graph();
  std::vector<std::vector<xodr::LaneNode>> sides(conflicts.conflict_count());
  for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
    for (const auto& zone : conflicts.zones(node)) {
      sides[zone.conflict].push_back(node);
    }
  }
  size_t merges = 0;
  for (const auto& pair : sides) {
    REQUIRE(pair.size() == 2);
    for (const bool at_start : {false, true}) {
      for (const auto& end : graph.ends(pair[0], at_start)) {
        CHECK(end.node != pair[1]);
      }
    }
    merges += map.road(graph.info(pair[0]).lane.road).id == "1194" ||
              map.road(graph.info(pair[1]).lane.road).id == "1194";
  }
  CHECK(merges > 0);  // the ramp still gives way where it merges
}

TEST_CASE("Four generated cars arriving at a four-way junction at once all get through",
          "[engine][npc][give_way]") {
  Crossing crossing(intersection_text());
  std::vector<uint32_t> cars;
  for (int arm = 1; arm <= 4; ++arm) {
    cars.push_back(crossing.car_on_arm(arm, 30.0, 10.0));
  }
  crossing.run(25.0);
  INFO(crossing.overlaps);
  CHECK(crossing.overlaps.empty());
  for (int arm = 1; arm <= 4; ++arm) {
    INFO("car from arm " << arm);
    CHECK(crossing.through(cars[arm - 1], arm));
  }
  // Not all at once: some waited.
  const double slowest =
      *std::min_element(crossing.least_speed.begin(), crossing.least_speed.end());
  CHECK(slowest < 1.0);
  // Let go, each sped up within a generated car's acceleration (3 m/s^2), not at once to its
  // set speed.
  for (const double gain : crossing.most_gain) {
    CHECK(gain <= 3.0 + 1e-6);
  }
}

TEST_CASE("A generated car named as --npc names its vehicles is no NPC unless --npc placed it",
          "[engine][npc][give_way]") {
  // The four cars of the test above, named npc_vehicle_0 to npc_vehicle_3 either way (a traffic
  // action whose trafficName is npc_vehicle names its objects so too). Told by the name, the
  // traffic action's cars were NPCs: let go, they sped up within their acceleration. Not
  // placed by --npc, they take their set speed at once, as the scenario's traffic does.
  for (const bool npc : {true, false}) {
    INFO((npc ? "placed by --npc" : "a traffic action's"));
    Crossing crossing(intersection_text());
    for (int arm = 1; arm <= 4; ++arm) {
      const uint32_t car = crossing.car_on_arm(arm, 30.0, 10.0, npc);
      CHECK(crossing.state.world.entities[car].info.name ==
            "npc_vehicle_" + std::to_string(arm - 1));
    }
    crossing.run(25.0);
    CHECK(*std::min_element(crossing.least_speed.begin(), crossing.least_speed.end()) < 1.0);
    const double most_gain =
        *std::max_element(crossing.most_gain.begin(), crossing.most_gain.end());
    if (npc) {
      CHECK(most_gain <= 3.0 + 1e-6);
    } else {
      CHECK(most_gain > 100.0);  // from a stop to about its set speed in one 0.01 s step
    }
  }
}

TEST_CASE("Two generated cars placed too near the crossing they share to stop firmly do not meet",
          "[engine][npc][give_way]") {
  // Car 0 from arm 1 at 13.2 m/s, car 1 from arm 2 at 10.8 m/s (Town04 seed 5's pair at
  // 1.15 s, both placed about 10 m before their crossing): neither can stop before it at 5
  // m/s^2, so both were committed to it and drove into each other. Car 1 (the later in the
  // order) can still stop at its 8 m/s^2 (its side of the crossing begins about 4 m past the
  // junction's edge), and is told to.
  size_t emergencies = 0;
  for (const double first : {3.0, 5.0, 7.0}) {
    for (const double second : {6.0, 7.0, 8.0, 9.0}) {
      INFO("car 0 " << first << " m, car 1 " << second << " m before the junction");
      Crossing crossing(intersection_text());
      crossing.car_on_arm(1, first, 13.2);
      crossing.car_on_arm(2, second, 10.8);
      crossing.run(6.0);
      INFO(crossing.overlaps);
      CHECK(crossing.overlaps.empty());
      emergencies += crossing.hardest[1] > engine::detail::kFirm + 1.0;
      CHECK(crossing.hardest[1] <= 8.0 + 1e-6);  // never harder than it can
    }
  }
  CHECK(emergencies > 0);
}

TEST_CASE("A generated car on the priority road is not stopped by one that came first",
          "[engine][npc][give_way]") {
  // Arms 1 and 3 give way; the car from arm 1 is nearer the junction than the one from arm 2.
  Crossing crossing(with_give_way_sign(with_give_way_sign(intersection_text(), "1"), "3"));
  const uint32_t minor = crossing.car_on_arm(1, 15.0, 8.0);
  const uint32_t major = crossing.car_on_arm(2, 35.0, 10.0);
  crossing.run(15.0);
  INFO(crossing.overlaps);
  CHECK(crossing.overlaps.empty());
  CHECK(crossing.least_speed[major] > 9.0);  // never braked
  CHECK(crossing.least_speed[minor] < 1.0);  // waited for it
  CHECK(crossing.through(major, 2));
  CHECK(crossing.through(minor, 1));
}

TEST_CASE("A junction's priorities give right of way where no sign does",
          "[engine][npc][give_way]") {
  using engine::detail::RightOfWay;
  // Arm 2's connecting roads over arm 1's, pairwise.
  const std::string text =
      with_priorities(intersection_text(), {"104", "105", "106"}, {"101", "102", "103"});
  const auto map = map_of(text);
  const auto conflicts = engine::detail::JunctionConflicts::build(*map);
  CHECK(roads_with(*map, conflicts, RightOfWay::kPriority) ==
        std::set<std::string>{"104", "105", "106"});
  CHECK(roads_with(*map, conflicts, RightOfWay::kGiveWay) ==
        std::set<std::string>{"101", "102", "103"});
  // A road named both high and low is left normal; a sign on the incoming road wins.
  const auto mixed_map = map_of(with_priorities(with_give_way_sign(text, "2"), {"107"}, {"104"}));
  const auto mixed = engine::detail::JunctionConflicts::build(*mixed_map);
  CHECK(roads_with(*mixed_map, mixed, RightOfWay::kPriority) == std::set<std::string>{"107"});
  CHECK(roads_with(*mixed_map, mixed, RightOfWay::kGiveWay) ==
        std::set<std::string>{"101", "102", "103", "104", "105", "106"});
  // Driven: the car from arm 1 is nearer the junction, yet waits for the one from arm 2.
  Crossing crossing(text);
  const uint32_t minor = crossing.car_on_arm(1, 15.0, 8.0);
  const uint32_t major = crossing.car_on_arm(2, 35.0, 10.0);
  crossing.run(15.0);
  INFO(crossing.overlaps);
  CHECK(crossing.overlaps.empty());
  CHECK(crossing.least_speed[major] > 9.0);
  CHECK(crossing.least_speed[minor] < 1.0);
  CHECK(crossing.through(major, 2));
  CHECK(crossing.through(minor, 1));
}

// The yield points of vehicles 0 and 1 after one settling of their approaches.
std::vector<engine::detail::YieldPoint> settle_pair(
    const std::vector<engine::detail::Approach>& approaches) {
  const std::vector<uint32_t> who = {0, 1};
  std::vector<engine::detail::YieldPoint> yields(2);
  engine::detail::ClaimSettler settler;
  settler.settle(approaches, who, 2, yields);
  return yields;
}

TEST_CASE("A car crawling up to the point it waits at is not let into the zone it waits for",
          "[engine][npc][give_way]") {
  using engine::detail::Claim;
  // Town04 seed 1 at 7.11 s: car 0 waits for zone 0 (3.5 m ahead), crawling at 5 cm/s; zone 1,
  // which only it claims, begins 2 m ahead of its front. Car 1 has come later and can no longer
  // stop before its side of zone 0. Counting the whole stop margin at any speed, car 0 counted
  // as unable to stop before zone 1, went first as committed and took zone 0 too: both drove
  // into it (car 0 jumped to its set speed, having no leader left).
  const std::vector<engine::detail::Approach> approaches = {
      approach(0.05, 0, {Claim{1, 1, 1.999, 11, 4.2}, Claim{0, 1, 3.49, 11, 5.7}}),
      approach(8.9, 425, {Claim{0, 0, 1.42, 12, 11.1}})};
  std::vector<engine::detail::YieldPoint> yields = settle_pair(approaches);
  CHECK(yields[0].node == 11);  // stops before zone 0
  CHECK(yields[0].s == 5.7);
  CHECK(yields[1].node == xodr::kNoLane);
  // Crawling up to 1.6 m of zone 0 (where it had to stop from 1.5 m/s), it still waits.
  const std::vector<engine::detail::Approach> nearer = {
      approach(1.5, 0, {Claim{0, 1, 1.6, 11, 5.7}}), approaches[1]};
  yields = settle_pair(nearer);
  CHECK(yields[0].node == 11);
}

TEST_CASE("A car committed to one zone waits before the next for a car that cannot stop",
          "[engine][npc][give_way]") {
  using engine::detail::Claim;
  // Car 0, first to arrive, cannot stop before zone 1 but can before zone 0, 20 m on; car 1
  // cannot stop before its side of zone 0. Both committed, car 0 came first in the order and
  // took zone 0 as well: car 1 could not stop, and both drove into it.
  const std::vector<engine::detail::Approach> approaches = {
      approach(10.0, 100, {Claim{1, 0, 1.0, 21, 2.0}, Claim{0, 0, 20.0, 21, 21.0}}),
      approach(10.0, 200, {Claim{0, 1, 1.5, 22, 8.0}})};
  std::vector<engine::detail::YieldPoint> yields = settle_pair(approaches);
  CHECK(yields[0].node == 21);  // waits before zone 0
  CHECK(yields[0].s == 21.0);
  CHECK(yields[1].node == xodr::kNoLane);
}

TEST_CASE("A car that can stop before a zone only at its maximum deceleration is told to brake so",
          "[engine][npc][give_way]") {
  using engine::detail::Claim;
  // Town04 seed 5 at 1.15 s: car 0 placed at 13.2 m/s with its front 10.0 m before the
  // crossing (17.4 m to stop firmly, 10.9 m at 8 m/s^2), car 1 at 10.8 m/s 10.2 m before it
  // (11.7 m firmly, 7.3 m at 8 m/s^2). Neither counted as able to stop, and both went.
  const std::vector<engine::detail::Approach> approaches = {
      approach(13.2, 0, {Claim{0, 0, 10.0, 31, 4.0}}),
      approach(10.8, 0, {Claim{0, 1, 10.2, 32, 6.0}})};
  std::vector<engine::detail::YieldPoint> yields = settle_pair(approaches);
  CHECK(yields[0].node == xodr::kNoLane);
  CHECK(yields[1].node == 32);
  CHECK(yields[1].s == 6.0);
  CHECK(yields[1].emergency);
  // One that can stop firmly is told to stop without an emergency; one that cannot stop even at
  // its maximum deceleration goes on.
  const std::vector<engine::detail::Approach> gentler = {
      approaches[0], approach(8.0, 0, {Claim{0, 1, 10.2, 32, 6.0}})};
  yields = settle_pair(gentler);
  CHECK(yields[1].node == 32);
  CHECK_FALSE(yields[1].emergency);
  const std::vector<engine::detail::Approach> weaker = {
      approaches[0], approach(10.8, 0, {Claim{0, 1, 10.2, 32, 6.0}}, 5.0)};
  yields = settle_pair(weaker);
  CHECK(yields[1].node == xodr::kNoLane);
}

TEST_CASE("A walker about to cross waits for a vehicle coming close to its way",
          "[engine][npc][give_way]") {
  const xosc::Scenario scenario;
  Diagnostics diagnostics;
  engine::detail::SimState state(scenario, nullptr, engine::SimulationOptions{}, diagnostics);
  const auto add = [&](double x, double y, double h, double speed, const engine::Box& box,
                       engine::ObjectKind kind) { add_entity(state, x, y, h, speed, box, kind); };
  // The walker at the kerb at the origin, facing across the road (+y).
  add(0.0, 0.0, 0.5 * std::numbers::pi, 0.0, {0.0, 0.0, 0.9, 0.5, 0.6, 1.8},
      engine::ObjectKind::kPedestrian);
  state.traffic.lifetimes[0];
  // A car 30 m to the left in the near lane, coming at 10 m/s.
  add(-30.0, 1.75, 0.0, 10.0, {1.4, 0.0, 0.75, 4.5, 1.8, 1.5}, engine::ObjectKind::kVehicle);
  engine::detail::FollowView view;
  std::vector<uint32_t> near;
  const auto waits = [&] {
    view.build(state, true);
    return engine::detail::walker_waits(state.world.entities[0], 0, view, 8.0, near);
  };
  CHECK(waits());
  // Going away from the walker's way, standing far off, or passed: no reason to wait.
  state.world.entities[1].write_state().pose.h = std::numbers::pi;
  CHECK_FALSE(waits());
  state.world.entities[1].write_state().pose.h = 0.0;
  state.world.entities[1].write_state().speed = 0.0;
  CHECK_FALSE(waits());
  state.world.entities[1].write_state().speed = 10.0;
  state.world.entities[1].write_state().pose.x = 8.0;
  CHECK_FALSE(waits());
  // Far away at that speed: it is not close within the next seconds.
  state.world.entities[1].write_state().pose.x = -80.0;
  CHECK_FALSE(waits());
  // Standing in the walker's way: waits.
  state.world.entities[1].write_state().pose.x = -1.0;
  state.world.entities[1].write_state().speed = 0.0;
  CHECK(waits());
}

TEST_CASE("A walker keeps clear of one that stopped turned on its right", "[engine][npc][walker]") {
  const xosc::Scenario scenario;
  Diagnostics diagnostics;
  engine::detail::SimState state(scenario, nullptr, engine::SimulationOptions{}, diagnostics);
  const engine::Box walker_box{0.0, 0.0, 0.9, 0.5, 0.6, 1.8};
  const auto add = [&](double x, double y, double h, double speed) {
    add_entity(state, x, y, h, speed, walker_box, engine::ObjectKind::kPedestrian);
  };
  // Walking along +x at 1.5 m/s; the other stands 0.6 m ahead, 0.66 m to the right, facing
  // back at 0.4 rad off our way (it stopped while stepping aside): its turned box reaches 0.72 m
  // across, farther than two walkers side by side (0.65 m).
  add(0.0, 0.0, 0.0, 1.5);
  add(0.6, -0.66, std::numbers::pi + 0.4, 0.0);
  engine::detail::FollowView view;
  std::vector<uint32_t> near;
  const auto move = [&] {
    view.build(state, true);
    return engine::detail::walker_move(state.world.entities[0], 0, view, 1.5, near);
  };
  engine::detail::WalkerMove seen = move();
  CHECK(seen.speed == 0.0);   // does not walk into it
  CHECK(seen.lateral > 0.0);  // steps left, away from it
  // Facing straight back it is no wider than a walker: passed at walking speed, stepping left.
  state.world.entities[1].write_state().pose.h = std::numbers::pi;
  seen = move();
  CHECK(seen.speed == 1.5);
  CHECK(seen.lateral > 0.0);
  // Coming on our left, both keep right.
  state.world.entities[1].write_state().pose.y = 0.66;
  seen = move();
  CHECK(seen.lateral < 0.0);
}

}  // namespace corsa::test
