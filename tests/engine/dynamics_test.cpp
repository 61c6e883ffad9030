// The dynamics controller: a single-track vehicle model driven by pure pursuit and a speed PI
// loop. Its vehicles change lanes with plausible lateral acceleration, stay within their
// Performance limits and are deterministic. The vehicle models of all dynamics vehicles of a step
// are integrated as one ARKODE system (controllers/dynamics_fleet.h) with classic RK4 at the
// engine's 10 ms step: these tests pin down that this changes no vehicle's result (the system is
// block diagonal) and how close the 10 ms step stays to a reference run with 1 ms steps under
// the same inputs.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "controllers/dynamics_fleet.h"
#include "controllers/dynamics_model.h"
#include "engine_fixture.h"
#include "motorway_fleet.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using corsa::engine::detail::DynamicsFleet;
using corsa::engine::detail::DynamicsIntegrator;
using corsa::engine::detail::VehicleInputs;
using corsa::engine::detail::VehicleParams;
using corsa::engine::detail::VehicleState;

using InputsAt = std::function<VehicleInputs(double)>;  // inputs held over the step from t (s)

struct Maneuver {
  const char* name;
  double speed;     // m/s at the start
  double duration;  // s
  InputsAt inputs;
};

// A motorway lane change at 25 m/s (a steering sinusoid over 4 s), and a tight turn at low speed
// with full steering while accelerating: about 7 m/s^2 of lateral acceleration, in the
// saturating part of the tyre curve, and the model's fastest mode (about -17 g / vx per second)
// at its stiffest.
std::vector<Maneuver> maneuvers() {
  return {{"lane change at 25 m/s", 25.0, 8.0,
           [](double t) {
             VehicleInputs in;
             in.steer =
                 t > 1.0 && t < 5.0 ? 0.02 * std::sin(std::numbers::pi * (t - 1.0) / 2.0) : 0.0;
             in.accel = t < 4.0 ? 0.5 : -1.0;
             return in;
           }},
          {"tight turn from 4 m/s", 4.0, 6.0, [](double t) {
             VehicleInputs in;
             in.steer = t > 0.5 ? 0.4 : 0.0;
             in.accel = 0.5;
             return in;
           }}};
}

// Runs a maneuver with engine steps of 10 ms, each integrated in `substeps` equal steps.
std::vector<VehicleState> run_maneuver(const Maneuver& maneuver, int substeps,
                                       const VehicleParams& params = {}) {
  DynamicsFleet fleet;
  DynamicsIntegrator model(params);
  VehicleState start;
  start.vx = maneuver.speed;
  model.reset(start);
  std::vector<VehicleState> states;
  const double dt = 0.01;
  const auto steps = static_cast<int>(std::lround(maneuver.duration / dt));
  for (int i = 0; i < steps; ++i) {
    const VehicleInputs in = maneuver.inputs(i * dt);
    for (int k = 0; k < substeps; ++k) {
      model.begin_step(in, dt / substeps, fleet);
      fleet.integrate(dt / substeps);
    }
    states.push_back(model.state());
  }
  return states;
}

struct Deviation {
  double position = 0.0;  // m
  double yaw = 0.0;       // rad
  double speed = 0.0;     // m/s
};

Deviation max_deviation(const std::vector<VehicleState>& a, const std::vector<VehicleState>& b) {
  REQUIRE(a.size() == b.size());
  Deviation d;
  for (size_t i = 0; i < a.size(); ++i) {
    d.position = std::max(d.position, std::hypot(a[i].x - b[i].x, a[i].y - b[i].y));
    d.yaw = std::max(d.yaw, std::abs(a[i].yaw - b[i].yaw));
    d.speed = std::max(d.speed, std::hypot(a[i].vx - b[i].vx, a[i].vy - b[i].vy));
  }
  return d;
}

constexpr double kLaneWidth = 3.5;  // straight.xodr

// Vehicles on the bundled 2 km motorway, all under --controller dynamics: `count` of them, the
// first changing lanes after 2 s, the others at other speeds in other lanes.
std::vector<FleetVehicle> motorway_vehicles(int count) {
  std::vector<FleetVehicle> vehicles;
  for (int i = 0; i < count; ++i) {
    FleetVehicle v;
    v.name = "V" + std::to_string(i);
    v.lane = -1 - i % 3;
    v.s = 100 + 40 * i;
    v.speed = 20 + 3 * i;
    if (i == 0) {
      v.lane_change.emplace();
      v.lane_change->lanes = -1;
      v.lane_change->after = 2.0;
    }
    vehicles.push_back(v);
  }
  return vehicles;
}

// The states of V0 at every step of 10 s with `count` dynamics vehicles.
std::vector<corsa::engine::EntityState> first_vehicle_trace(int count) {
  corsa::Diagnostics diagnostics;
  const auto scenario = corsa::xosc::parse_scenario(
      motorway_fleet_scenario(motorway_vehicles(count), "dynamics fleet"), motorway_fleet_path(),
      {}, diagnostics);
  corsa::engine::SimulationOptions options;
  options.duration = 10.0;
  options.controller = "dynamics";
  corsa::engine::Simulation sim(scenario, corsa::engine::load_road_network(scenario, diagnostics),
                                options, diagnostics);
  corsa::test::TraceRecorder trace;
  sim.add_observer(trace);
  sim.run();
  std::vector<corsa::engine::EntityState> states;
  for (const auto& [tick, all] : trace.ticks()) {
    states.push_back(all.at(0));
  }
  return states;
}

TEST_CASE("The dynamics vehicle tracks a lane change with plausible lateral acceleration",
          "[engine][controllers][dynamics]") {
  FixtureRun run(engine_fixture("controller_dynamics_lane_change.xosc"));
  run.run();
  const size_t dyn = run.entity("Dyn");
  double peak_lateral = 0.0, peak_yaw_rate = 0.0, max_deviation = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const auto& s = states.at(dyn);
    REQUIRE(s.road);
    // a_y = v * yaw rate on a straight road (the heading's rate is the path's curvature).
    peak_lateral = std::max(peak_lateral, std::abs(s.speed * s.yaw_rate));
    peak_yaw_rate = std::max(peak_yaw_rate, std::abs(s.yaw_rate));
    // It never wanders beyond the two lanes it uses.
    max_deviation = std::max(max_deviation, std::abs(s.road->t + 2.5 * kLaneWidth));
  }
  // The commanded sinusoid over 4 s peaks at pi^2 * 3.5 / (2 * 16) = 1.08 m/s^2; the driver
  // model follows with some lag and overshoot, well inside comfort and friction limits.
  CHECK(peak_lateral > 0.5);
  CHECK(peak_lateral < 3.0);
  CHECK(max_deviation < 1.5 * kLaneWidth);
  const auto& end = run.now("Dyn");
  REQUIRE(end.road);
  CHECK(end.road->lane == -2);
  CHECK(end.road->t == Approx(-1.5 * kLaneWidth).margin(0.15));
  CHECK(std::abs(end.pose.h) < 0.01);
  CHECK(end.speed == Approx(20.0).margin(0.3));
  // The ideal vehicle made the same change exactly.
  const auto& ideal = run.now("Ideal");
  REQUIRE(ideal.road);
  CHECK(ideal.road->t == Approx(-1.5 * kLaneWidth).margin(1e-6));
}

TEST_CASE("The dynamics vehicle stays within its Performance limits",
          "[engine][controllers][dynamics]") {
  FixtureRun run(engine_fixture("controller_dynamics_limits.xosc"));
  run.run();
  const size_t dyn = run.entity("Dyn");
  double top = 0.0, max_acc = 0.0, max_dec = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const auto& s = states.at(dyn);
    top = std::max(top, s.speed);
    max_acc = std::max(max_acc, s.acceleration);
    max_dec = std::max(max_dec, -s.acceleration);
    CHECK(s.speed >= 0.0);
  }
  CHECK(top <= 25.1);  // maxSpeed 25 although 40 was asked for (actuator lag: a little over)
  CHECK(top > 24.0);
  CHECK(max_acc <= 2.0 * 1.001);  // maxAcceleration (integration tolerance)
  CHECK(max_acc > 1.8);
  CHECK(max_dec <= 4.0 * 1.001);  // maxDeceleration
  CHECK(max_dec > 3.5);
  CHECK(run.now("Dyn").speed == Approx(0.0).margin(1e-3));  // braked to a stop by 24 s
}

TEST_CASE("The dynamics controller is deterministic", "[engine][controllers][dynamics]") {
  FixtureRun a(engine_fixture("controller_dynamics_lane_change.xosc"));
  FixtureRun b(engine_fixture("controller_dynamics_lane_change.xosc"));
  a.run();
  b.run();
  REQUIRE(a.trace().ticks().size() == b.trace().ticks().size());
  for (const auto& [tick, states] : a.trace().ticks()) {
    const auto& other = b.trace().at(tick, 0);
    CHECK(states[0].pose.x == other.pose.x);
    CHECK(states[0].pose.y == other.pose.y);
    CHECK(states[0].pose.h == other.pose.h);
  }
}

TEST_CASE("The vehicle models of a step integrated as one system give each what it gets alone",
          "[engine][controllers][dynamics]") {
  VehicleParams heavy;
  heavy.mass = 12000.0;
  heavy.yaw_inertia = 60000.0;
  heavy.wheelbase = 5.5;
  heavy.cg_to_rear = 2.0;
  heavy.friction = 0.6;
  const std::vector<VehicleParams> params = {VehicleParams{}, heavy, VehicleParams{}};
  const auto all = maneuvers();
  const std::vector<Maneuver> chosen = {all[0], all[0], all[1]};
  std::vector<std::vector<VehicleState>> alone;
  for (size_t v = 0; v < chosen.size(); ++v) {
    alone.push_back(run_maneuver(chosen[v], 1, params[v]));
  }
  // Together, in one fleet, which also takes vehicles joining and leaving: the third joins
  // after 1 s and stops after 6 s, before the others.
  DynamicsFleet fleet;
  std::vector<std::unique_ptr<DynamicsIntegrator>> models;
  for (size_t v = 0; v < chosen.size(); ++v) {
    models.push_back(std::make_unique<DynamicsIntegrator>(params[v]));
    VehicleState start;
    start.vx = chosen[v].speed;
    models.back()->reset(start);
  }
  // Step `i` of the fleet is step i - first[v] of vehicle v.
  const size_t first[3] = {0, 0, 100};
  const double dt = 0.01;
  for (size_t i = 0; i < alone[0].size(); ++i) {
    const auto runs = [&](size_t v) { return i >= first[v] && i - first[v] < alone[v].size(); };
    for (size_t v = 0; v < chosen.size(); ++v) {
      if (runs(v)) {
        models[v]->begin_step(chosen[v].inputs(static_cast<double>(i - first[v]) * dt), dt, fleet);
      }
    }
    fleet.integrate(dt);
    for (size_t v = 0; v < chosen.size(); ++v) {
      if (runs(v)) {
        CAPTURE(v, i);
        const VehicleState& got = models[v]->state();
        const VehicleState& want = alone[v][i - first[v]];
        REQUIRE(got.x == want.x);
        REQUIRE(got.y == want.y);
        REQUIRE(got.yaw == want.yaw);
        REQUIRE(got.vx == want.vx);
        REQUIRE(got.vy == want.vy);
        REQUIRE(got.yaw_rate == want.yaw_rate);
      }
    }
  }
}

TEST_CASE("RK4 at the engine's 10 ms step stays within a stated tolerance of a 1 ms reference",
          "[engine][controllers][dynamics]") {
  for (const Maneuver& maneuver : maneuvers()) {
    CAPTURE(maneuver.name);
    const auto reference = run_maneuver(maneuver, 10);
    const Deviation at_10ms = max_deviation(run_maneuver(maneuver, 1), reference);
    const Deviation at_5ms = max_deviation(run_maneuver(maneuver, 2), reference);
    CAPTURE(at_10ms.position, at_10ms.yaw, at_10ms.speed, at_5ms.position);
    // The stated tolerance: 1 mm, 0.1 mrad and 1 mm/s over the whole maneuver, far below what
    // lane positions, contacts and conditions resolve. Measured: 4e-8 m on the motorway lane
    // change, 8e-5 m in the tight turn, where the fastest mode is stiffest (h lambda = -0.4).
    CHECK(at_10ms.position < 1e-3);
    CHECK(at_10ms.yaw < 1e-4);
    CHECK(at_10ms.speed < 1e-3);
    // Fourth order: halving the step divides the error by about 16 (SUNDIALS 6.4's ERKStep,
    // left to itself, would reuse the last stage's derivative as the next step's first one and
    // the ratio would be about 8 or less).
    CHECK(at_10ms.position > 12.0 * at_5ms.position);
  }
}

TEST_CASE("A dynamics vehicle moves the same whether or not other dynamics vehicles share its run",
          "[engine][controllers][dynamics]") {
  const auto alone = first_vehicle_trace(1);
  const auto with_others = first_vehicle_trace(6);
  REQUIRE(alone.size() > 900);
  REQUIRE(alone.size() == with_others.size());
  for (size_t i = 0; i < alone.size(); ++i) {
    CAPTURE(i);
    REQUIRE(alone[i].pose.x == with_others[i].pose.x);
    REQUIRE(alone[i].pose.y == with_others[i].pose.y);
    REQUIRE(alone[i].pose.h == with_others[i].pose.h);
    REQUIRE(alone[i].speed == with_others[i].speed);
  }
  // It did change lanes (the run is not trivially the same).
  REQUIRE(alone.back().road);
  CHECK(alone.back().road->lane == -2);
}

}  // namespace
}  // namespace corsa::test
