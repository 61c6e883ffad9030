// Engine stepping throughput (issue #5: above 2 million entity-steps per second on a
// 100-vehicle scenario). 100 cars on the bundled 2 km motorway, 50 each way in three lanes,
// every one with an event that changes its speed after a few seconds and every tenth a lane
// change; each iteration runs 10 s of simulated time (1,000 steps of 0.01 s) on a fresh
// Simulation built from the loaded scenario and map (building it is timed apart).
//
//   corsa_bench_engine [--benchmark_repetitions=5]   (Release build; median of the repetitions)

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace {

constexpr int kVehicles = 100;
constexpr int kSteps = 1000;

std::string vehicle_xml(int i) {
  std::ostringstream out;
  out << "<ScenarioObject name=\"V" << i << "\"><Vehicle name=\"car\" vehicleCategory=\"car\">"
      << "<Performance maxSpeed=\"60\" maxAcceleration=\"6\" maxDeceleration=\"9\"/>"
      << "<BoundingBox><Center x=\"1.4\" y=\"0\" z=\"0.75\"/>"
      << "<Dimensions width=\"1.8\" length=\"4.5\" height=\"1.5\"/></BoundingBox>"
      << "<Axles><FrontAxle maxSteering=\"0.5\" wheelDiameter=\"0.6\" trackWidth=\"1.6\" "
         "positionX=\"2.8\" positionZ=\"0.3\"/><RearAxle maxSteering=\"0\" wheelDiameter=\"0.6\" "
         "trackWidth=\"1.6\" positionX=\"0\" "
         "positionZ=\"0.3\"/></Axles></Vehicle></ScenarioObject>";
  return out.str();
}

// Vehicle i: lane 1..3 (toward -s) for even i, -1..-3 (toward +s) for odd i, 40 m apart.
std::string init_xml(int i) {
  const int lane = (i % 2 == 0 ? 1 : -1) * (1 + (i / 2) % 3);
  const int slot = i / 6;
  const double s = lane > 0 ? 1900.0 - 40.0 * slot : 100.0 + 40.0 * slot;
  std::ostringstream out;
  out << "<Private entityRef=\"V" << i << "\"><PrivateAction><TeleportAction><Position>"
      << "<LanePosition roadId=\"1\" laneId=\"" << lane << "\" s=\"" << s << "\"/>"
      << "</Position></TeleportAction></PrivateAction><PrivateAction><LongitudinalAction>"
      << "<SpeedAction><SpeedActionDynamics dynamicsShape=\"step\" value=\"0\" "
         "dynamicsDimension=\"time\"/><SpeedActionTarget><AbsoluteTargetSpeed value=\""
      << 25 + (i % 7) << "\"/></SpeedActionTarget></SpeedAction></LongitudinalAction>"
      << "</PrivateAction></Private>";
  return out.str();
}

std::string group_xml(int i) {
  std::ostringstream out;
  out << "<ManeuverGroup maximumExecutionCount=\"1\" name=\"G" << i << "\"><Actors "
      << "selectTriggeringEntities=\"false\"><EntityRef entityRef=\"V" << i << "\"/></Actors>"
      << "<Maneuver name=\"M\"><Event name=\"Vary\" priority=\"parallel\"><Action name=\"Speed\">"
      << "<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics "
         "dynamicsShape=\"cubic\" value=\"3\" dynamicsDimension=\"time\"/><SpeedActionTarget>"
         "<AbsoluteTargetSpeed value=\""
      << 22 + (i % 5) << "\"/></SpeedActionTarget></SpeedAction></LongitudinalAction>"
      << "</PrivateAction></Action><StartTrigger><ConditionGroup><Condition name=\"t\" "
         "delay=\"0\" conditionEdge=\"rising\"><ByValueCondition><SimulationTimeCondition value=\""
      << 1 + i % 6 << "\" rule=\"greaterThan\"/></ByValueCondition></Condition>"
      << "</ConditionGroup></StartTrigger></Event>";
  if (i % 10 == 0) {
    // Outer lanes move one lane in (to the left of their direction of travel).
    out << "<Event name=\"Change\" priority=\"parallel\"><Action name=\"Lane\"><PrivateAction>"
        << "<LateralAction><LaneChangeAction><LaneChangeActionDynamics dynamicsShape="
           "\"sinusoidal\" value=\"3\" dynamicsDimension=\"time\"/><LaneChangeTarget>"
           "<RelativeTargetLane entityRef=\"V"
        << i << "\" value=\"" << ((i / 2) % 3 == 2 ? 1 : 0) << "\"/></LaneChangeTarget>"
        << "</LaneChangeAction></LateralAction></PrivateAction></Action><StartTrigger>"
        << "<ConditionGroup><Condition name=\"near\" delay=\"0\" conditionEdge=\"none\">"
        << "<ByEntityCondition><TriggeringEntities triggeringEntitiesRule=\"any\"><EntityRef "
           "entityRef=\"V"
        << i
        << "\"/></TriggeringEntities><EntityCondition><TraveledDistanceCondition "
           "value=\"60\"/></EntityCondition></ByEntityCondition></Condition>"
        << "</ConditionGroup></StartTrigger></Event>";
  }
  out << "</Maneuver></ManeuverGroup>";
  return out.str();
}

std::string scenario_xml() {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?><OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
         "date=\"2026-01-01T00:00:00\" description=\"100 vehicles\" author=\"Corsa\"/>"
         "<ParameterDeclarations/><CatalogLocations/><RoadNetwork><LogicFile "
         "filepath=\"maps/motorway_2km.xodr\"/></RoadNetwork><Entities>";
  for (int i = 0; i < kVehicles; ++i) {
    out << vehicle_xml(i);
  }
  out << "</Entities><Storyboard><Init><Actions>";
  for (int i = 0; i < kVehicles; ++i) {
    out << init_xml(i);
  }
  out << "</Actions></Init><Story name=\"Traffic\"><Act name=\"Drive\">";
  for (int i = 0; i < kVehicles; ++i) {
    out << group_xml(i);
  }
  out << "</Act></Story><StopTrigger><ConditionGroup><Condition name=\"end\" delay=\"0\" "
         "conditionEdge=\"none\"><ByValueCondition><SimulationTimeCondition value=\"3600\" "
         "rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>"
         "</Storyboard></OpenSCENARIO>";
  return out.str();
}

struct Fixture {
  corsa::Diagnostics diagnostics;
  corsa::xosc::Scenario scenario;
  std::shared_ptr<const corsa::xodr::Map> map;

  Fixture()
      : scenario(corsa::xosc::parse_scenario(
            scenario_xml(), std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/traffic.xosc", {},
            diagnostics)),
        map(corsa::engine::load_road_network(scenario, diagnostics)) {}
};

Fixture& fixture() {
  static Fixture instance;  // built once, read-only afterwards
  return instance;
}

void BM_Step100Vehicles(benchmark::State& state) {
  Fixture& f = fixture();
  int64_t entity_steps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    corsa::engine::Simulation sim(f.scenario, f.map, {}, f.diagnostics);
    state.ResumeTiming();
    for (int i = 0; i < kSteps; ++i) {
      sim.step();
    }
    entity_steps += static_cast<int64_t>(kSteps) * kVehicles;
    benchmark::DoNotOptimize(sim.state(0).pose.x);
  }
  state.counters["entity_steps_per_s"] =
      benchmark::Counter(static_cast<double>(entity_steps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Step100Vehicles)->Unit(benchmark::kMillisecond);

void BM_Build100Vehicles(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    corsa::engine::Simulation sim(f.scenario, f.map, {}, f.diagnostics);
    benchmark::DoNotOptimize(sim.entity_count());
  }
}
BENCHMARK(BM_Build100Vehicles)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
