// The dynamics controller (issue #6: a 50-vehicle scenario under it above 100x real time).
// 50 cars on the bundled 2 km motorway, 25 each way in three lanes 50 m apart, each with a
// speed change after a few seconds and every fifth a lane change; all under `--controller
// dynamics` (SimulationOptions::controller). Each repetition runs 30 s of simulated time
// (3,000 steps of 0.01 s) on a fresh Simulation; the default controller is timed alongside.
//
//   corsa_bench_dynamics [REPETITIONS] [CONTROLLER...]
//
// Release build; prints the median of the repetitions (default 5) for each controller (default:
// dynamics, acc, default), and the load average, since wall time on a shared machine includes
// waiting for a core. Instruction counts of one controller's run, which do not depend on the
// load: valgrind --tool=callgrind corsa_bench_dynamics 1 dynamics

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace {

constexpr int kVehicles = 50;
constexpr double kSimSeconds = 30.0;

std::string speed_action(double value, const char* shape, double time) {
  std::ostringstream out;
  out << "<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape=\""
      << shape << "\" value=\"" << time
      << "\" dynamicsDimension=\"time\"/><SpeedActionTarget><AbsoluteTargetSpeed value=\"" << value
      << "\"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>";
  return out.str();
}

std::string scenario_xml() {
  std::ostringstream entities, init, groups;
  for (int i = 0; i < kVehicles; ++i) {
    const int lane = (i % 2 == 0 ? -1 : 1) * (1 + (i / 2) % 3);
    const int slot = i / 6;
    const double s = lane < 0 ? 100.0 + 50.0 * slot : 1900.0 - 50.0 * slot;
    entities << "<ScenarioObject name=\"D" << i << "\"><Vehicle name=\"car\" "
             << "vehicleCategory=\"car\"><Performance maxSpeed=\"50\" maxAcceleration=\"4\" "
             << "maxDeceleration=\"8\"/><BoundingBox><Center x=\"1.4\" y=\"0\" z=\"0.75\"/>"
             << "<Dimensions width=\"1.8\" length=\"4.5\" height=\"1.5\"/></BoundingBox><Axles>"
             << "<FrontAxle maxSteering=\"0.5\" wheelDiameter=\"0.6\" trackWidth=\"1.6\" "
             << "positionX=\"2.8\" positionZ=\"0.3\"/><RearAxle maxSteering=\"0\" "
             << "wheelDiameter=\"0.6\" trackWidth=\"1.6\" positionX=\"0\" positionZ=\"0.3\"/>"
             << "</Axles></Vehicle></ScenarioObject>";
    init << "<Private entityRef=\"D" << i << "\"><PrivateAction><TeleportAction><Position>"
         << "<LanePosition roadId=\"1\" laneId=\"" << lane << "\" s=\"" << s << "\"/>"
         << "</Position></TeleportAction></PrivateAction>" << speed_action(24 + i % 5, "step", 0)
         << "</Private>";
    groups << "<ManeuverGroup maximumExecutionCount=\"1\" name=\"G" << i << "\"><Actors "
           << "selectTriggeringEntities=\"false\"><EntityRef entityRef=\"D" << i << "\"/>"
           << "</Actors><Maneuver name=\"M\"><Event name=\"Vary\" priority=\"parallel\">"
           << "<Action name=\"Speed\">" << speed_action(20 + i % 7, "cubic", 4) << "</Action>"
           << "<StartTrigger><ConditionGroup><Condition name=\"t\" delay=\"0\" "
           << "conditionEdge=\"rising\"><ByValueCondition><SimulationTimeCondition value=\""
           << 2 + i % 8 << "\" rule=\"greaterThan\"/></ByValueCondition></Condition>"
           << "</ConditionGroup></StartTrigger></Event>";
    if (i % 5 == 0) {
      // Toward the middle lane: the outer lanes move left, the others right.
      const int delta = std::abs(lane) == 1 ? -1 : 1;
      groups << "<Event name=\"Change\" priority=\"parallel\"><Action name=\"Lane\">"
             << "<PrivateAction><LateralAction><LaneChangeAction><LaneChangeActionDynamics "
             << "dynamicsShape=\"sinusoidal\" value=\"4\" dynamicsDimension=\"time\"/>"
             << "<LaneChangeTarget><RelativeTargetLane entityRef=\"D" << i << "\" value=\""
             << (std::abs(lane) == 2 ? 0 : delta) << "\"/></LaneChangeTarget>"
             << "</LaneChangeAction></LateralAction></PrivateAction></Action><StartTrigger>"
             << "<ConditionGroup><Condition name=\"t\" delay=\"0\" conditionEdge=\"rising\">"
             << "<ByValueCondition><SimulationTimeCondition value=\"" << 12 + i % 6
             << "\" rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup>"
             << "</StartTrigger></Event>";
    }
    groups << "</Maneuver></ManeuverGroup>";
  }
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?><OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
         "date=\"2026-01-01T00:00:00\" description=\"50 vehicles, dynamics\" author=\"Corsa\"/>"
         "<ParameterDeclarations/><CatalogLocations/><RoadNetwork><LogicFile "
         "filepath=\"maps/motorway_2km.xodr\"/></RoadNetwork><Entities>"
      << entities.str() << "</Entities><Storyboard><Init><Actions>" << init.str()
      << "</Actions></Init><Story name=\"Traffic\"><Act name=\"Drive\">" << groups.str()
      << "</Act></Story><StopTrigger><ConditionGroup><Condition name=\"end\" delay=\"0\" "
         "conditionEdge=\"none\"><ByValueCondition><SimulationTimeCondition value=\"3600\" "
         "rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>"
         "</Storyboard></OpenSCENARIO>";
  return out.str();
}

struct Timing {
  double wall = 0.0;  ///< s
  double cpu = 0.0;   ///< s of this process's CPU time (the machine is shared: wall time includes
                      ///< waiting for a core)
};

// Median wall and CPU times (s) of `repetitions` runs of kSimSeconds under `controller`.
Timing median_run(const corsa::xosc::Scenario& scenario,
                  const std::shared_ptr<const corsa::xodr::Map>& map, const std::string& controller,
                  int repetitions, corsa::Diagnostics& diagnostics) {
  std::vector<double> walls, cpus;
  for (int r = 0; r < repetitions; ++r) {
    corsa::engine::SimulationOptions options;
    options.duration = kSimSeconds;
    options.controller = controller;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    corsa::engine::Simulation sim(scenario, map, options, diagnostics);
    sim.run();
    cpus.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    walls.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(walls.begin(), walls.end());
  std::sort(cpus.begin(), cpus.end());
  return {walls[walls.size() / 2], cpus[cpus.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<std::string> controllers(argv + std::min(argc, 2), argv + argc);
  if (controllers.empty()) {
    controllers = {"dynamics", "acc", "default"};
  }
  corsa::Diagnostics diagnostics;
  const auto scenario = corsa::xosc::parse_scenario(
      scenario_xml(), std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/dynamics.xosc", {},
      diagnostics);
  const auto map = corsa::engine::load_road_network(scenario, diagnostics);
  for (const std::string& controller : controllers) {
    const Timing t = median_run(scenario, map, controller, repetitions, diagnostics);
    std::printf(
        "%-8s %d vehicles, %.0f s simulated: median %.3f s wall (%.0fx real time), %.3f s CPU "
        "(%.0fx)\n",
        controller.c_str(), kVehicles, kSimSeconds, t.wall, kSimSeconds / t.wall, t.cpu,
        kSimSeconds / t.cpu);
  }
  double load[3] = {0.0, 0.0, 0.0};
  if (getloadavg(load, 3) == 3) {
    std::printf("load average %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  }
  return 0;
}
