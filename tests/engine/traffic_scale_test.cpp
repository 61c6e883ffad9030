// Large traffic: car followers read the others as they were when the step began (so the order
// of the entities and the number of threads do not change a run), the neighbour structures
// behind car following and spawning answer as a scan of every entity would, and the work a
// standing entity costs does not change what it records.

#include <algorithm>
#include <atomic>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contact_pairs.h"
#include "controllers/follow_view.h"
#include "controllers/npc_caution.h"
#include "controllers/worker_pool.h"
#include "corsa/core/random.h"
#include "corsa/engine/outputs.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "engine_fixture.h"
#include "motorway_fleet.h"
#include "state/lane_index.h"
#include "state/packed_point_grid.h"
#include "state/point_grid.h"
#include "state/sim_state.h"
#include "state/world_contacts.h"
#include "test_entity.h"

namespace {

using corsa::Diagnostics;
using corsa::engine::Simulation;
using corsa::engine::SimulationOptions;

using corsa::engine::detail::same_bits;
using corsa::test::pairs_by_testing_all;

// Twelve cars in one lane and its neighbour, close enough to follow each other, at different
// speeds, some slowing down; every third changes lanes.
std::vector<corsa::test::FleetVehicle> queue() {
  std::vector<corsa::test::FleetVehicle> vehicles;
  for (int i = 0; i < 12; ++i) {
    corsa::test::FleetVehicle v;
    v.name = "Q" + std::to_string(i);
    v.lane = i % 2 == 0 ? -1 : -2;
    v.s = 100.0 + 18.0 * i;
    v.speed = 30.0 - 1.5 * i;
    if (i % 4 == 1) {
      v.speed_change = corsa::test::FleetVehicle::SpeedChange{8.0, 2.0, 1.0 + 0.5 * i};
    }
    if (i % 3 == 0) {
      corsa::test::FleetVehicle::LaneChange change;
      change.lanes = i % 2 == 0 ? -1 : 1;
      change.after = 2.0 + 0.1 * i;
      v.lane_change = change;
    }
    vehicles.push_back(v);
  }
  return vehicles;
}

// Every entity's state by name at every tick.
struct Trace {
  std::vector<std::string> names;
  std::vector<std::vector<corsa::engine::EntityState>> ticks;
};

Trace run_fleet(const std::vector<corsa::test::FleetVehicle>& vehicles) {
  Diagnostics diagnostics;
  const auto scenario =
      corsa::xosc::parse_scenario(corsa::test::motorway_fleet_scenario(vehicles, "queue"),
                                  corsa::test::motorway_fleet_path(), {}, diagnostics);
  SimulationOptions options;
  options.controller = "acc";
  options.duration = 12.0;
  Simulation sim(scenario, corsa::engine::load_road_network(scenario, diagnostics), options,
                 diagnostics);
  Trace trace;
  for (size_t i = 0; i < sim.entity_count(); ++i) {
    trace.names.push_back(sim.entity(i).name);
  }
  do {
    std::vector<corsa::engine::EntityState> states;
    for (size_t i = 0; i < sim.entity_count(); ++i) {
      states.push_back(sim.state(i));
    }
    trace.ticks.push_back(std::move(states));
  } while (sim.step());
  return trace;
}

bool same_state(const corsa::engine::EntityState& a, const corsa::engine::EntityState& b) {
  return same_bits(a.pose.x, b.pose.x) && same_bits(a.pose.y, b.pose.y) &&
         same_bits(a.pose.h, b.pose.h) && same_bits(a.speed, b.speed) &&
         same_bits(a.acceleration, b.acceleration) && same_bits(a.odometer, b.odometer);
}

// The trajectory CSV of a run of `scenario` with `options`, every step.
std::string trajectory_rows(const corsa::xosc::Scenario& scenario,
                            const std::shared_ptr<const corsa::xodr::Map>& map,
                            const SimulationOptions& options) {
  Diagnostics diagnostics;
  Simulation sim(scenario, map, options, diagnostics);
  std::string rows;
  do {
    corsa::engine::TrajectoryRecorder::append_rows(sim, rows);
  } while (sim.step());
  return rows;
}

}  // namespace

TEST_CASE("Car followers drive the same whatever the order the scenario lists them in",
          "[engine][acc][traffic]") {
  const auto forward = queue();
  auto backward = forward;
  std::reverse(backward.begin(), backward.end());
  const Trace a = run_fleet(forward);
  const Trace b = run_fleet(backward);
  REQUIRE(a.ticks.size() == b.ticks.size());
  REQUIRE(a.names.size() == b.names.size());
  const size_t n = a.names.size();
  size_t compared = 0;
  for (size_t i = 0; i < n; ++i) {
    const size_t j = n - 1 - i;
    REQUIRE(a.names[i] == b.names[j]);
    for (size_t t = 0; t < a.ticks.size(); ++t) {
      if (!same_state(a.ticks[t][i], b.ticks[t][j])) {
        FAIL_CHECK(a.names[i] << " differs at tick " << t);
        break;
      }
      ++compared;
    }
  }
  CHECK(compared == n * a.ticks.size());
  // The queue is close enough that car following acts: the slowing cars hold the ones behind.
  const auto& last = a.ticks.back();
  CHECK(last[3].speed < 29.0);
}

TEST_CASE("Many vehicles give byte-identical trajectories on 1, 2 and 3 threads",
          "[engine][traffic][threads]") {
  Diagnostics diagnostics;
  const auto scenario = corsa::xosc::parse_scenario(
      "<?xml version=\"1.0\"?><OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
      "date=\"2026-01-01T00:00:00\" description=\"npc\" author=\"Corsa\"/>"
      "<ParameterDeclarations/><CatalogLocations/><RoadNetwork><LogicFile filepath=\"" +
          (std::filesystem::path(CORSA_SHARED_DIR) / "data/xodr/Town04.xodr").string() +
          "\"/></RoadNetwork><Entities/><Storyboard><Init><Actions/></Init><StopTrigger/>"
          "</Storyboard></OpenSCENARIO>",
      corsa::test::engine_fixture("town04_npc.xosc"), {}, diagnostics);
  const auto map = corsa::engine::load_road_network(scenario, diagnostics);
  SimulationOptions options;
  options.duration = 4.0;
  options.seed = 7;
  options.npc.vehicles = 400;
  options.npc.pedestrians = 40;
  options.threads = 1;
  const std::string one = trajectory_rows(scenario, map, options);
  options.threads = 2;
  const std::string two = trajectory_rows(scenario, map, options);
  options.threads = 3;
  const std::string three = trajectory_rows(scenario, map, options);
  CHECK(one.size() > 401 * 440 * 50);  // every step, every entity
  CHECK(one == two);
  CHECK(one == three);
}

TEST_CASE("Contacts among hundreds of vehicles are the same on 1 and 2 threads",
          "[engine][traffic][threads]") {
  // 240 cars in the three lanes of one direction, 12 m apart in each lane, at speeds from 10
  // to 33 m/s under the default controller (which does not mind the others): the faster run
  // into and through the slower ones, so boxes start to overlap all through the run.
  std::vector<corsa::test::FleetVehicle> cars;
  for (int i = 0; i < 240; ++i) {
    corsa::test::FleetVehicle v;
    v.name = std::string("C").append(std::to_string(i));
    v.lane = -1 - i % 3;
    v.s = 20.0 + 4.0 * i;
    v.speed = 10.0 + (i * 7) % 24;
    cars.push_back(v);
  }
  // The story needs a maneuver group: a speed change after the run.
  cars[0].speed_change = corsa::test::FleetVehicle::SpeedChange{20.0, 1.0, 100.0};
  Diagnostics diagnostics;
  const auto scenario =
      corsa::xosc::parse_scenario(corsa::test::motorway_fleet_scenario(cars, "contacts"),
                                  corsa::test::motorway_fleet_path(), {}, diagnostics);
  const auto map = corsa::engine::load_road_network(scenario, diagnostics);
  const auto contacts = [&](unsigned threads) {
    SimulationOptions options;
    options.duration = 3.0;
    options.threads = threads;
    Diagnostics run_diagnostics;
    Simulation sim(scenario, map, options, run_diagnostics);
    sim.run();
    std::vector<std::string> records;
    for (const corsa::engine::CollisionRecord& c : sim.collisions()) {
      records.push_back(std::to_string(c.tick) + ":" + std::to_string(c.first) + "-" +
                        std::to_string(c.second));
    }
    return records;
  };
  const std::vector<std::string> one = contacts(1);
  const std::vector<std::string> two = contacts(2);
  CHECK(one.size() > 100);
  CHECK(one == two);
}

TEST_CASE("The lane index finds every entity of a lane within an s range, in s order",
          "[engine][traffic]") {
  corsa::RandomStream random(11);
  corsa::engine::detail::LaneIndex index;
  struct Item {
    uint32_t node;
    double s;
  };
  for (int round = 0; round < 3; ++round) {
    std::vector<Item> items;
    index.reset(20);
    for (uint32_t i = 0; i < 500; ++i) {
      items.push_back(
          {static_cast<uint32_t>(random.uniform_int(0, 19)), random.uniform(0.0, 300.0)});
      index.add(items.back().node, items.back().s, i);
    }
    index.finish();
    CHECK(index.size() == 500);
    for (int q = 0; q < 200; ++q) {
      const auto node = static_cast<uint32_t>(random.uniform_int(0, 19));
      const double low = random.uniform(-10.0, 300.0);
      const double high = low + random.uniform(0.0, 120.0);
      std::vector<uint32_t> found;
      index.query(node, low, high, found);
      std::vector<uint32_t> expected;
      for (uint32_t i = 0; i < items.size(); ++i) {
        if (items[i].node == node && items[i].s >= low && items[i].s <= high) {
          expected.push_back(i);
        }
      }
      for (size_t k = 1; k < found.size(); ++k) {
        CHECK(items[found[k - 1]].s <= items[found[k]].s);
      }
      std::sort(found.begin(), found.end());
      CHECK(found == expected);
    }
  }
}

TEST_CASE(
    "The lane index orders a lane by s and entity however its entities were added, and gives "
    "its order back",
    "[engine][traffic]") {
  corsa::RandomStream random(13);
  corsa::engine::detail::LaneIndex index;
  // Lane 0: 300 entities, some at equal s (entity breaks the tie); lane 1: 5. Added in entity
  // order (random s), in the last order with a few moved (nearly sorted: the insertion sort),
  // and backwards (past its budget: std::sort).
  std::vector<double> s(305);
  for (double& v : s) v = std::round(random.uniform(0.0, 100.0) * 4.0) / 4.0;
  const auto lane_of = [](uint32_t i) { return i < 300 ? 0u : 1u; };
  const auto sorted = [&](uint32_t lane) {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < s.size(); ++i) {
      if (lane_of(i) == lane) out.push_back(i);
    }
    std::sort(out.begin(), out.end(),
              [&](uint32_t a, uint32_t b) { return s[a] < s[b] || (s[a] == s[b] && a < b); });
    return out;
  };
  const auto entities = [&](uint32_t lane) {
    std::vector<uint32_t> out;
    for (const auto& entry : index.lane(lane)) out.push_back(entry.entity);
    return out;
  };
  const auto fill = [&](const std::vector<uint32_t>& order) {
    index.reset(2);
    for (const uint32_t i : order) index.add(lane_of(i), s[i], i);
    index.finish();
    CHECK(entities(0) == sorted(0));
    CHECK(entities(1) == sorted(1));
  };
  std::vector<uint32_t> order(s.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  fill(order);
  std::vector<uint32_t> last;
  index.order(last);
  std::vector<uint32_t> both = sorted(0);
  const std::vector<uint32_t> second = sorted(1);
  both.insert(both.end(), second.begin(), second.end());
  CHECK(last == both);
  for (int k = 0; k < 10; ++k) s[static_cast<size_t>(random.uniform_int(0, 304))] += 0.3;
  fill(last);
  std::reverse(last.begin(), last.end());
  fill(last);
}

TEST_CASE("The point grid returns every point within the radius of a query", "[engine][traffic]") {
  corsa::RandomStream random(5);
  corsa::engine::detail::PointGrid grid(16.0);
  std::vector<std::pair<double, double>> points;
  for (uint32_t i = 0; i < 2000; ++i) {
    points.emplace_back(random.uniform(-500.0, 500.0), random.uniform(-300.0, 300.0));
    grid.add(points.back().first, points.back().second, i);
  }
  grid.add(std::nan(""), 0.0, 2000);  // a point nowhere: every query returns it
  for (int q = 0; q < 300; ++q) {
    const double x = random.uniform(-550.0, 550.0), y = random.uniform(-350.0, 350.0);
    const double r = random.uniform(0.5, 40.0);
    std::vector<uint32_t> found;
    grid.query(x, y, r, found);
    std::sort(found.begin(), found.end());
    CHECK(std::binary_search(found.begin(), found.end(), 2000u));
    for (uint32_t i = 0; i < points.size(); ++i) {
      if (std::hypot(points[i].first - x, points[i].second - y) <= r) {
        CHECK(std::binary_search(found.begin(), found.end(), i));
      }
    }
  }
}

TEST_CASE("The packed point grid returns every point of a box or a tilted band, as a scan would",
          "[engine][traffic]") {
  corsa::RandomStream random(11);
  corsa::engine::detail::PackedPointGrid grid(8.0);
  std::vector<std::pair<double, double>> points;
  for (int round = 0; round < 2; ++round) {  // the second round refills the grid in place
    grid.clear();
    points.clear();
    for (uint32_t i = 0; i < 1500; ++i) {
      // Some points on cell borders and on one spot: the cases rounding could get wrong.
      const double x =
          i % 7 == 0 ? 8.0 * random.uniform_int(-40, 40) : random.uniform(-330.0, 330.0);
      const double y = i % 11 == 0 ? 24.0 : random.uniform(-210.0, 210.0);
      points.emplace_back(x, y);
      grid.add(x, y, i);
    }
    grid.add(std::nan(""), 0.0, 1500);  // a point nowhere: every query returns it
    grid.finish();
    CHECK(grid.size() == points.size());
    for (int q = 0; q < 300; ++q) {
      const double x = random.uniform(-360.0, 360.0), y = random.uniform(-240.0, 240.0);
      const double h = random.uniform(-3.2, 3.2), c = std::cos(h), s = std::sin(h);
      const double along_min = random.uniform(-10.0, 0.0), along_max = random.uniform(0.0, 60.0);
      const double half = random.uniform(0.5, 12.0);
      double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
      for (const double a : {along_min, along_max}) {
        for (const double b : {-half, half}) {
          x_min = std::min(x_min, x + a * c - b * s), x_max = std::max(x_max, x + a * c - b * s);
          y_min = std::min(y_min, y + a * s + b * c), y_max = std::max(y_max, y + a * s + b * c);
        }
      }
      x_min -= 0.01, y_min -= 0.01, x_max += 0.01, y_max += 0.01;
      std::vector<uint32_t> band, box;
      grid.query_band(x_min, y_min, x_max, y_max, x, y, c, s, along_min, along_max, half, band);
      grid.query_box(x_min, y_min, x_max, y_max, box);
      std::vector<uint32_t> in_band, in_box;
      for (uint32_t i = 0; i < points.size(); ++i) {
        const double dx = points[i].first - x, dy = points[i].second - y;
        const double along = dx * c + dy * s, across = -dx * s + dy * c;
        if (along >= along_min && along <= along_max && std::abs(across) <= half) {
          in_band.push_back(i);
        }
        if (points[i].first >= x_min && points[i].first <= x_max && points[i].second >= y_min &&
            points[i].second <= y_max) {
          in_box.push_back(i);
        }
      }
      in_band.push_back(1500);
      std::sort(band.begin(), band.end());
      CHECK(band == in_band);  // the band test is exact: nothing more, nothing less
      std::sort(box.begin(), box.end());
      CHECK(std::includes(box.begin(), box.end(), in_box.begin(), in_box.end()));
      CHECK(std::binary_search(box.begin(), box.end(), 1500u));
    }
    std::vector<uint32_t> all;
    grid.query_box(std::nan(""), 0.0, 1.0, 1.0, all);  // no region: every point
    CHECK(all.size() == points.size() + 1);
    std::vector<uint32_t> none;
    grid.query_box(1e6, 1e6, 2e6, 2e6, none);
    CHECK(none == std::vector<uint32_t>{1500});
  }
}

TEST_CASE(
    "The band query keeps what a filter of its box's cells keeps, in the same order, on dense and "
    "sparse layouts, far from the origin too",
    "[engine][traffic]") {
  corsa::RandomStream random(23);
  corsa::engine::detail::PackedPointGrid grid(8.0);
  for (int layout = 0; layout < 6; ++layout) {
    grid.clear();
    std::vector<std::pair<double, double>> points;
    // Dense layouts (small cells) and sparse ones (cells made larger), far from the origin too.
    const uint32_t count = layout % 2 == 0 ? 3000 : 150;
    const double ox = layout < 4 ? 0.0 : 2.5e5, oy = layout < 4 ? 0.0 : -1.5e5;
    for (uint32_t i = 0; i < count; ++i) {
      points.emplace_back(ox + random.uniform(-400.0, 400.0), oy + random.uniform(-250.0, 250.0));
    }
    // Queries: long thin corridors and short wide ones at every heading, from inside and outside
    // the points' extent; some points on each band's edges and corners, where rounding decides.
    struct Query {
      double x, y, c, s, along_min, along_max, half;
    };
    std::vector<Query> queries;
    for (int q = 0; q < 200; ++q) {
      const double h = q % 10 == 0 ? (q / 10) * std::numbers::pi / 4.0 : random.uniform(-3.2, 3.2);
      const bool thin = q % 2 == 0;
      queries.push_back({ox + random.uniform(-450.0, 450.0), oy + random.uniform(-300.0, 300.0),
                         std::cos(h), std::sin(h), random.uniform(-45.0, 0.0),
                         random.uniform(0.0, thin ? 150.0 : 20.0),
                         thin ? random.uniform(0.0, 2.5) : random.uniform(2.0, 30.0)});
      const Query& b = queries.back();
      for (const double a : {b.along_min, b.along_max, 0.5 * (b.along_min + b.along_max)}) {
        for (const double across : {-b.half, b.half}) {
          points.emplace_back(b.x + a * b.c - across * b.s, b.y + a * b.s + across * b.c);
        }
      }
    }
    for (uint32_t i = 0; i < points.size(); ++i) grid.add(points[i].first, points[i].second, i);
    grid.finish();
    uint32_t kept = 0;
    for (const Query& b : queries) {
      double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
      for (const double a : {b.along_min, b.along_max}) {
        for (const double across : {-b.half, b.half}) {
          const double wx = b.x + a * b.c - across * b.s, wy = b.y + a * b.s + across * b.c;
          x_min = std::min(x_min, wx), x_max = std::max(x_max, wx);
          y_min = std::min(y_min, wy), y_max = std::max(y_max, wy);
        }
      }
      std::vector<uint32_t> band, box, filtered, scanned;
      grid.query_band(x_min, y_min, x_max, y_max, b.x, b.y, b.c, b.s, b.along_min, b.along_max,
                      b.half, band);
      // Its box's cells, filtered: the order the outputs' bytes depend on (a query that looked
      // at fewer cells would have to keep it).
      grid.query_box(x_min, y_min, x_max, y_max, box);
      const auto in_band = [&](uint32_t i) {
        const double dx = points[i].first - b.x, dy = points[i].second - b.y;
        const double along = dx * b.c + dy * b.s, across = -dx * b.s + dy * b.c;
        return along >= b.along_min && along <= b.along_max && std::abs(across) <= b.half;
      };
      std::copy_if(box.begin(), box.end(), std::back_inserter(filtered), in_band);
      CHECK(band == filtered);
      // And a scan of every point (the box may leave out a point rounding puts on its border).
      for (uint32_t i = 0; i < points.size(); ++i) {
        if (in_band(i)) scanned.push_back(i);
      }
      std::sort(band.begin(), band.end());
      CHECK(band == scanned);
      kept += static_cast<uint32_t>(band.size());
    }
    CHECK(kept > queries.size());  // the bands hold points: the comparisons are not of nothing
  }
}

TEST_CASE(
    "The band query keeps hundreds of points of one cell in their order, appended to what the "
    "list held",
    "[engine][traffic]") {
  // More points in the band than the query's buffer holds (it goes to the list in blocks), half
  // of them outside the band's sides, and the list not empty before the query.
  corsa::RandomStream random(31);
  corsa::engine::detail::PackedPointGrid grid(8.0);
  std::vector<std::pair<double, double>> points;
  for (uint32_t i = 0; i < 1200; ++i) {
    points.emplace_back(random.uniform(0.0, 6.0), random.uniform(-2.0, 2.0));
    grid.add(points.back().first, points.back().second, i);
  }
  grid.finish();
  const double c = std::cos(0.3), s = std::sin(0.3);
  std::vector<uint32_t> band = {7777, 8888};
  grid.query_band(-10.0, -10.0, 20.0, 20.0, 0.0, 0.0, c, s, 0.5, 5.5, 1.0, band);
  std::vector<uint32_t> expected = {7777, 8888};
  for (uint32_t i = 0; i < points.size(); ++i) {
    const double along = points[i].first * c + points[i].second * s;
    const double across = -points[i].first * s + points[i].second * c;
    if (along >= 0.5 && along <= 5.5 && std::abs(across) <= 1.0) expected.push_back(i);
  }
  // One cell: the points in the order they were added.
  CHECK(band == expected);
  CHECK(expected.size() > 2 + 2 * 128);
  CHECK(expected.size() < 2 + points.size());
}

TEST_CASE(
    "A generated vehicle's corridor holds the boxes that reach into it, wherever their reference "
    "points are",
    "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
  const auto add = [&](double x, double y, double h, const corsa::engine::Box& box) {
    detail::Entity entity = corsa::test::entity_of(box);
    entity.write_state().placed = true;
    entity.write_state().pose.x = x;
    entity.write_state().pose.y = y;
    entity.write_state().pose.h = h;
    state.world.entities.push_back(std::move(entity));
  };
  // The generated car at the origin, heading along x: its front 3.65 m ahead, its corridor
  // 0.9 + 0.5 m either side.
  add(0.0, 0.0, 0.0, {1.4, 0.0, 0.75, 4.5, 1.8, 1.5});
  state.traffic.lifetimes[0];
  // Its reference point in the corridor, its box 7-9 m to the left: not in the way.
  add(10.0, 0.0, 0.0, {0.0, 8.0, 0.75, 4.0, 2.0, 1.5});
  // Its reference point 9 m to the left and its box's centre 7 m to its right, reaching from
  // y = 0 to y = 4 and from x = 18 to x = 22: in the way 14.35 m ahead.
  add(20.0, 9.0, 0.0, {0.0, -7.0, 0.75, 4.0, 4.0, 1.5});
  // A bus across the road, its reference point at its front 11.6 m off the corridor, its box
  // 12 m behind that (x from 28.75 to 31.25, y from -13 to -1): in the way 25.1 m ahead.
  add(30.0, -13.0, -std::numbers::pi / 2.0, {-6.0, 0.0, 1.5, 12.0, 2.5, 3.0});
  detail::FollowView view;
  view.build(state, true);
  std::vector<uint32_t> near;
  const double any = std::numeric_limits<double>::infinity();
  const detail::Hazard hazard =
      detail::corridor_hazard(state.world.entities[0], 0, view, 20.0, any, near);
  CHECK(hazard.gap == Approx(14.35));
  // Asked farther, the box at 14.35 m is still the nearest.
  CHECK(detail::corridor_hazard(state.world.entities[0], 0, view, 60.0, any, near).gap ==
        Approx(14.35));
  // Gaps below 14.4 m wanted: the same; below 14.3 m: none of the two is.
  CHECK(detail::corridor_hazard(state.world.entities[0], 0, view, 60.0, 14.4, near).gap ==
        Approx(14.35));
  CHECK_FALSE(detail::corridor_hazard(state.world.entities[0], 0, view, 60.0, 14.3, near).gap <
              14.3);
  // Without that box the bus is the nearest, and beyond a corridor of 20 m there is nothing.
  state.world.entities[2].write_state().placed = false;
  view.build(state, true);
  CHECK(detail::corridor_hazard(state.world.entities[0], 0, view, 60.0, any, near).gap ==
        Approx(25.1));
  CHECK(std::isinf(detail::corridor_hazard(state.world.entities[0], 0, view, 20.0, any, near).gap));
}

TEST_CASE(
    "A corridor asked only for gaps below a bound finds the same nearest box below it, to the bit",
    "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
  std::mt19937 random(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Cars, walkers and trucks around a few hundred metres from the origin, many of them in lanes
  // ahead of one another along the generated cars' headings, some across: the exact tests then
  // see boxes that pass the bounding test at every distance.
  for (int i = 0; i < 400; ++i) {
    const bool in_line = i % 3 != 0;
    const double along = 60.0 * unit(random);
    corsa::engine::Pose pose;
    pose.x = 300.0 + (in_line ? along : 60.0 * unit(random));
    pose.y = -200.0 + (in_line ? 0.8 * (unit(random) - 0.5) + 3.5 * (i % 2) : 60.0 * unit(random));
    pose.h = in_line ? 0.05 * (unit(random) - 0.5) : 6.3 * unit(random);
    const double length = i % 7 == 0 ? 12.0 : (i % 5 == 0 ? 0.5 : 4.5);
    const double width = i % 5 == 0 && i % 7 != 0 ? 0.6 : 1.9;
    detail::Entity entity =
        corsa::test::entity_of({1.4 * unit(random), 0.0, 0.75, length, width, 1.5});
    entity.write_state().placed = true;
    entity.write_state().pose = pose;
    state.world.entities.push_back(std::move(entity));
    if (i % 4 == 0) {
      state.traffic.lifetimes[static_cast<uint32_t>(i)];
    }
  }
  detail::FollowView view;
  view.build(state, true);
  std::vector<uint32_t> near;
  const double any = std::numeric_limits<double>::infinity();
  int found = 0;
  for (uint32_t i = 0; i < state.world.entities.size(); i += 4) {
    const detail::Entity& me = state.world.entities[i];
    const detail::Hazard all = detail::corridor_hazard(me, i, view, 40.0, any, near);
    found += std::isfinite(all.gap) ? 1 : 0;
    for (const double wanted : {-1.0, 0.0, all.gap, std::nextafter(all.gap, any), all.gap + 0.005,
                                all.gap + 1.0, 5.0, 20.0}) {
      const detail::Hazard some = detail::corridor_hazard(me, i, view, 40.0, wanted, near);
      if (all.gap < wanted) {
        CHECK(std::bit_cast<uint64_t>(some.gap) == std::bit_cast<uint64_t>(all.gap));
        CHECK(std::bit_cast<uint64_t>(some.speed) == std::bit_cast<uint64_t>(all.speed));
      } else {
        CHECK_FALSE(some.gap < wanted);
      }
    }
  }
  CHECK(found > 40);
}

TEST_CASE(
    "A speed along another heading is the speed times the cosine of the difference, to the bit",
    "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double headings[] = {0.0, -0.0, 1e-300, 0.3, -2.9, 3.141592653589793, 1e6, inf, nan};
  for (const double speed : {0.0, -0.0, 13.7, -2.5, 1e-310, inf, nan}) {
    for (const double h : headings) {
      for (const double own : headings) {
        const double expected = speed * std::cos(h - own);
        const double got = detail::speed_along(speed, h, own);
        CHECK((std::bit_cast<uint64_t>(got) == std::bit_cast<uint64_t>(expected) ||
               (std::isnan(got) && std::isnan(expected))));
      }
    }
  }
  // Equal headings skip the cosine and keep the speed itself.
  CHECK(std::bit_cast<uint64_t>(detail::speed_along(-0.0, 0.7, 0.7)) ==
        std::bit_cast<uint64_t>(-0.0));
}

TEST_CASE("The contacts of many boxes of every size and heading are the pairs a test of all finds",
          "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  // Walkers, cars and a few 18 m trucks at random headings, dense in a small square and sparse
  // around it, spread more along x in one layout and along y in the other; a few not placed or
  // without a box; then moved a little, as a step does.
  for (const bool along_y : {false, true}) {
    detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
    corsa::RandomStream random(along_y ? 7 : 5);
    const auto place = [&](detail::Entity& entity, bool dense) {
      const double spread = dense ? 60.0 : 2000.0;
      const double wide = random.uniform(-spread, spread);
      const double narrow = random.uniform(-spread / 4.0, spread / 4.0);
      entity.write_state().pose.x = along_y ? narrow : wide;
      entity.write_state().pose.y = along_y ? wide : narrow;
      entity.write_state().pose.h = random.uniform(-std::numbers::pi, std::numbers::pi);
    };
    for (int i = 0; i < 900; ++i) {
      const int kind = random.uniform_int(0, 19);
      detail::Entity entity =
          corsa::test::entity_of(kind == 0     ? corsa::engine::Box{0.0, 0.0, 2.0, 18.0, 2.6, 4.0}
                                 : kind < 5    ? corsa::engine::Box{0.0, 0.0, 0.9, 0.6, 0.6, 1.8}
                                 : i % 89 == 5 ? corsa::engine::Box{}
                                               : corsa::engine::Box{1.4, 0.0, 0.75, 4.5, 1.8, 1.5});
      entity.write_state().placed = i % 97 != 3;
      place(entity, i % 4 != 0);
      state.world.entities.push_back(std::move(entity));
    }
    const auto all_pairs = [&] { return pairs_by_testing_all(state.world.entities); };
    detail::ContactSweep sweep;
    detail::update_contacts(state, sweep);
    const auto first = all_pairs();
    CHECK(state.contacts.pairs == first);
    CHECK(first.size() > 100);
    CHECK(state.collisions.size() == first.size());
    for (detail::Entity& entity : state.world.entities) {
      entity.write_state().pose.x += random.uniform(-1.0, 1.0);
      entity.write_state().pose.y += random.uniform(-1.0, 1.0);
    }
    detail::update_contacts(state, sweep);
    const auto second = all_pairs();
    CHECK(state.contacts.pairs == second);
    // Only the pairs that were not touching before are new collisions.
    size_t fresh = 0;
    for (const auto& pair : second) {
      fresh += std::binary_search(first.begin(), first.end(), pair) ? 0 : 1;
    }
    CHECK(fresh > 0);
    CHECK(state.collisions.size() == first.size() + fresh);
  }
}

TEST_CASE("Many boxes over a small area are swept in strips and give the pairs a test of all finds",
          "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  // 700 walkers, cars and 18 m trucks at random headings over 400 m x 160 m (longer along x in
  // one layout, along y in the other): the one sweep would meet several boxes per box, so the
  // sweep runs in strips of 16 m across its axis; trucks and a third of the cars reach across a
  // strip's border. Then every box moves a little and the sweep runs again.
  for (const bool along_y : {false, true}) {
    CAPTURE(along_y);
    detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
    corsa::RandomStream random(along_y ? 11 : 13);
    for (int i = 0; i < 700; ++i) {
      const int kind = random.uniform_int(0, 9);
      detail::Entity entity =
          corsa::test::entity_of(kind == 0  ? corsa::engine::Box{0.0, 0.0, 2.0, 18.0, 2.6, 4.0}
                                 : kind < 3 ? corsa::engine::Box{0.0, 0.0, 0.9, 0.6, 0.6, 1.8}
                                            : corsa::engine::Box{1.4, 0.0, 0.75, 4.5, 1.8, 1.5});
      entity.write_state().placed = true;
      const double wide = random.uniform(-200.0, 200.0);
      const double narrow = random.uniform(-80.0, 80.0);
      entity.write_state().pose.x = along_y ? narrow : wide;
      entity.write_state().pose.y = along_y ? wide : narrow;
      entity.write_state().pose.h = random.uniform(-std::numbers::pi, std::numbers::pi);
      state.world.entities.push_back(std::move(entity));
    }
    const auto all_pairs = [&] { return pairs_by_testing_all(state.world.entities); };
    detail::ContactSweep sweep;
    detail::update_contacts(state, sweep);
    CHECK(sweep.along_y == along_y);
    CHECK(sweep.strips >= 8);
    const auto first = all_pairs();
    CHECK(first.size() > 100);
    CHECK(state.contacts.pairs == first);
    for (detail::Entity& entity : state.world.entities) {
      entity.write_state().pose.x += random.uniform(-1.0, 1.0);
      entity.write_state().pose.y += random.uniform(-1.0, 1.0);
    }
    detail::update_contacts(state, sweep);
    CHECK(sweep.strips >= 8);
    CHECK(state.contacts.pairs == all_pairs());
  }
}

TEST_CASE(
    "Boxes exactly on the strips' borders and boxes across several strips give the pairs a "
    "test of all finds",
    "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  // Five rows of 40 boxes 4 m x 2 m, 3 m apart along the road (each touching its neighbours),
  // unturned so that the extents are exact: the lowest row's low edge across is at -1, where
  // the strips begin, and the strips are 16 m wide (203 boxes over 66 m: 12 wanted, none
  // narrower than 16 m), so their borders are at 15, 31, 47 and 63. Row 1 starts on border 15,
  // row 2 ends on border 31 where row 3 starts (the two rows touch on it), row 4 starts on
  // border 63; three boxes 40 m across span strips 0 to 3. Along y the same, x and y swapped.
  constexpr double kBorders[] = {15.0, 31.0, 47.0, 63.0};
  for (const bool along_y : {false, true}) {
    CAPTURE(along_y);
    detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
    const auto add = [&](double along, double across, double length, double width) {
      detail::Entity entity =
          corsa::test::entity_of(along_y ? corsa::engine::Box{0.0, 0.0, 0.75, width, length, 1.5}
                                         : corsa::engine::Box{0.0, 0.0, 0.75, length, width, 1.5});
      entity.write_state().placed = true;
      entity.write_state().pose.x = along_y ? across : along;
      entity.write_state().pose.y = along_y ? along : across;
      state.world.entities.push_back(std::move(entity));
    };
    for (const double row : {0.0, 16.0, 30.0, 32.0, 64.0}) {
      for (int i = 0; i < 40; ++i) add(3.0 * i + (row == 32.0 ? 1.5 : 0.0), row, 4.0, 2.0);
    }
    for (const double along : {10.0, 50.0, 90.0}) add(along, 32.0, 4.0, 40.0);
    detail::ContactSweep sweep;
    detail::update_contacts(state, sweep);
    CHECK(sweep.along_y == along_y);
    CHECK(sweep.strips == 5);
    // The extents across lie exactly on the borders.
    const auto& across = along_y ? sweep.x_extent : sweep.y_extent;
    size_t on_border = 0;
    for (const auto& extent : across) {
      for (const double border : kBorders) {
        on_border += static_cast<size_t>(extent.low == border) + (extent.high == border);
      }
    }
    CHECK(on_border == 4 * 40);
    const auto all = pairs_by_testing_all(state.world.entities);
    CHECK(all.size() > 200);
    CHECK(state.contacts.pairs == all);
    // The rows on border 31 touch each other, and the boxes across several strips touch rows 1
    // to 3.
    const auto touching = [&](uint32_t a, uint32_t b) {
      return std::binary_search(all.begin(), all.end(), std::pair{a, b});
    };
    CHECK(touching(2 * 40 + 5, 3 * 40 + 5));
    CHECK(touching(1 * 40 + 3, 200));
    CHECK(touching(3 * 40 + 3, 200));
  }
}

TEST_CASE("Boxes that moved into and out of contact with standing ones get a full sweep's contacts",
          "[engine][traffic]") {
  namespace detail = corsa::engine::detail;
  using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;
  const corsa::xosc::Scenario scenario;
  Diagnostics diagnostics;
  // 120 cars standing in two rows, 10 m apart along a road running east, or north (the sweep
  // along y), turned by up to 0.12 rad, cars 0 and 1 touching; then a few cars move (onto standing
  // ones, onto each other, away again) while the rest stand, so that the update tests the moved
  // boxes alone.
  constexpr uint32_t kCars = 120;
  for (const bool north : {false, true}) {
    CAPTURE(north);
    const auto pose_of = [&](double along, double across, double turn) {
      corsa::engine::Pose pose;
      pose.x = north ? across : along;
      pose.y = north ? along : across;
      pose.h = (north ? std::numbers::pi / 2.0 : 0.0) + turn;
      return pose;
    };
    std::vector<corsa::engine::Pose> poses;
    for (uint32_t i = 0; i < kCars; ++i) {
      poses.push_back(pose_of(10.0 * (i % 60) + (i == 1 ? -7.0 : 0.0), 3.5 * (i / 60), 0.001 * i));
    }
    // A state holding the cars at `poses`.
    const auto fill = [&](detail::SimState& state) {
      state.world.entities.clear();
      for (uint32_t i = 0; i < kCars; ++i) {
        detail::Entity entity =
            corsa::test::entity_of(corsa::engine::Box{1.4, 0.0, 0.75, 4.5, 1.8, 1.5});
        entity.write_state().placed = true;
        entity.write_state().pose = poses[i];
        state.world.entities.push_back(std::move(entity));
      }
    };
    // The contacts a sweep over every box finds, on a state of its own.
    const auto full_sweep = [&] {
      detail::SimState fresh(scenario, nullptr, SimulationOptions{}, diagnostics);
      fill(fresh);
      detail::ContactSweep sweep;
      detail::update_contacts(fresh, sweep);
      return fresh.contacts.pairs;
    };
    detail::SimState state(scenario, nullptr, SimulationOptions{}, diagnostics);
    fill(state);
    detail::ContactSweep sweep;
    detail::update_contacts(state, sweep);
    REQUIRE(state.contacts.pairs == Pairs{{0, 1}});
    REQUIRE(sweep.complete);
    REQUIRE(sweep.moved_mark.empty());  // only the update of the moved boxes marks them
    // Moves cars `which` to `to` in both `poses` and `state`, then updates the contacts.
    const auto move = [&](const std::vector<uint32_t>& which,
                          const std::vector<corsa::engine::Pose>& to) {
      for (size_t k = 0; k < which.size(); ++k) {
        poses[which[k]] = to[k];
        state.world.entities[which[k]].write_state().pose = to[k];
      }
      ++state.tick;
      // Emptied first: only the moved boxes' update sizes it again (a full sweep marks nothing).
      sweep.moved_mark.clear();
      detail::update_contacts(state, sweep);
      CHECK(sweep.moved == which);
      // The moved boxes' update ran, cleared its marks after and kept its result complete.
      REQUIRE(sweep.moved_mark.size() == kCars);
      CHECK(std::all_of(sweep.moved_mark.begin(), sweep.moved_mark.end(),
                        [](uint8_t mark) { return mark == 0; }));
      CHECK(sweep.complete);
      CHECK(state.contacts.pairs == full_sweep());
    };

    // Car 37 drives into car 80's rear, slightly askew: a new contact and a collision.
    move({37}, {pose_of(10.0 * 20 - 3.0, 3.5, 0.05)});
    CHECK(state.contacts.pairs == Pairs{{0, 1}, {37, 80}});
    REQUIRE(state.collisions.size() == 2);
    CHECK(state.collisions.back().first == 37);
    CHECK(state.collisions.back().second == 80);
    CHECK(state.collisions.back().tick == state.tick);
    // It backs off 2 m, about 0.4 m clear of car 80 and of car 79 behind it: the contact ends,
    // nothing new is recorded.
    move({37}, {pose_of(10.0 * 20 - 5.0, 3.5, 0.0)});
    CHECK(state.contacts.pairs == Pairs{{0, 1}});
    CHECK(state.collisions.size() == 2);
    // Cars 37 and 38 both move into the gap of row 0 at 52-55 m (onto each other and onto car
    // 5), while car 1 leaves car 0: each pair once, the two new ones recorded.
    move({1, 37, 38},
         {pose_of(15.0, -20.0, 0.0), pose_of(52.0, 0.3, 0.1), pose_of(53.5, -0.2, -0.1)});
    CHECK(state.contacts.pairs == Pairs{{5, 37}, {5, 38}, {37, 38}});
    REQUIRE(state.collisions.size() == 5);
    // Car 1 back onto car 0: that contact is new again.
    move({1}, {pose_of(3.0, 0.0, 0.01)});
    CHECK(state.contacts.pairs == Pairs{{0, 1}, {5, 37}, {5, 38}, {37, 38}});
    REQUIRE(state.collisions.size() == 6);
    CHECK(state.collisions.back().first == 0);
    CHECK(state.collisions.back().second == 1);
    // The last cars of both rows move back beside car 30, clear of it (the moved boxes' pairs
    // are merged with the kept ones: none changes), then car 59 into the crowd at 52 m: only
    // its new contacts are recorded.
    move({59, 119}, {pose_of(305.0, -3.5, 0.0), pose_of(305.0, 7.0, 0.0)});
    CHECK(state.contacts.pairs == Pairs{{0, 1}, {5, 37}, {5, 38}, {37, 38}});
    CHECK(state.collisions.size() == 6);
    move({59}, {pose_of(52.5, 1.6, 0.0)});
    REQUIRE(state.collisions.size() > 6);
    for (size_t k = 6; k < state.collisions.size(); ++k) {
      CHECK((state.collisions[k].first == 59 || state.collisions[k].second == 59));
    }
  }
}

TEST_CASE(
    "The worker pool hands out every item once, in chunks, announced or awaited or not, and "
    "rethrows a chunk's error",
    "[engine][traffic]") {
  using corsa::engine::detail::WorkerPool;
  for (const unsigned threads : {1u, 2u, 3u}) {
    WorkerPool pool(threads);
    REQUIRE(pool.threads() == threads);
    // Several runs in a row: each thread's share is set again for every run.
    for (const size_t count : {size_t{0}, size_t{1}, size_t{7}, size_t{64}, size_t{1000}}) {
      for (const size_t chunk : {size_t{1}, size_t{3}, size_t{32}}) {
        std::vector<std::atomic<int>> taken(count);
        std::atomic<bool> bad_range{false};
        // Runs announced ahead (the workers spin for them) and runs that are not, mixed.
        if (chunk != 3) {
          pool.prepare();
        }
        // After some runs the workers wait awake for the next (as between a step's picture
        // and its moves).
        const auto after = chunk == 32 ? WorkerPool::After::kAwait : WorkerPool::After::kSleep;
        pool.run(
            count, chunk,
            [&](size_t begin, size_t end, unsigned worker) {
              if (begin >= end || end > count || end - begin > chunk || begin % chunk != 0 ||
                  worker >= threads) {
                bad_range = true;
              }
              for (size_t i = begin; i < end; ++i) ++taken[i];
            },
            after);
        CHECK_FALSE(bad_range);
        size_t once = 0;
        for (const std::atomic<int>& t : taken) once += t.load() == 1 ? 1 : 0;
        CHECK(once == count);
      }
    }
    CHECK_THROWS_AS(pool.run(100, 8,
                             [](size_t begin, size_t, unsigned) {
                               if (begin == 48) throw std::runtime_error("chunk 6");
                             }),
                    std::runtime_error);
    std::atomic<size_t> sum{0};
    pool.run(100, 8, [&](size_t begin, size_t end, unsigned) { sum += end - begin; });
    CHECK(sum == 100);  // still hands out every item after an error
    // Announcements without a run (twice over, and one left when the pool ends) change nothing.
    pool.prepare();
    pool.prepare();
    sum = 0;
    pool.run(100, 8, [&](size_t begin, size_t end, unsigned) { sum += end - begin; });
    CHECK(sum == 100);
    pool.prepare();
    // A pool may end while its workers wait awake for a run that does not come.
    sum = 0;
    pool.run(
        100, 8, [&](size_t begin, size_t end, unsigned) { sum += end - begin; },
        WorkerPool::After::kAwait);
    CHECK(sum == 100);
  }
}
