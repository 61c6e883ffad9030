// The binary trajectory (corsa/engine/trajectory_file.h, docs/trajectory-format.md): its CSV
// export is the CSV the run writes, byte for byte; its rows read back the CSV's numbers; what
// does not move costs nothing; a file written by hand from the documented format reads; a
// damaged file is an error, never a crash.

#include "corsa/engine/trajectory_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/core/strings.h"
#include "corsa/engine/outputs.h"
#include "engine_fixture.h"
#include "output/decimal_text.h"
#include "output/trajectory_codec.h"
#include "output/trajectory_encoder.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace corsa::test {
namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

void write_all(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Runs `scenario` twice, recording CSV and binary; returns both file contents and the binary's
// CSV export.
struct Recorded {
  std::string csv;
  std::string binary;
  std::string exported;
};

Recorded record_both(const std::filesystem::path& scenario, int64_t every,
                     const engine::SimulationOptions& simulation = {}) {
  TempDir dir;
  for (const char* name : {"run.csv", "run.corsatraj"}) {
    engine::RunOptions options;
    options.scenario = scenario;
    options.simulation = simulation;
    options.record = dir.path() / name;
    options.record_every = every;
    Diagnostics diagnostics;
    engine::run_scenario(options, diagnostics);
  }
  Recorded out;
  out.csv = read_all(dir.path() / "run.csv");
  out.binary = read_all(dir.path() / "run.corsatraj");
  out.exported = engine::trajectory_csv_of(dir.path() / "run.corsatraj");
  return out;
}

// A varint / zigzag / little-endian writer, from the format's description (not the engine's).
struct Bytes {
  std::string data;
  Bytes& u8(uint8_t v) {
    data.push_back(static_cast<char>(v));
    return *this;
  }
  Bytes& var(uint64_t v) {
    while (v >= 0x80) {
      u8(static_cast<uint8_t>(v | 0x80));
      v >>= 7;
    }
    return u8(static_cast<uint8_t>(v));
  }
  Bytes& zig(int64_t v) { return var((static_cast<uint64_t>(v) << 1) ^ (v < 0 ? ~0ull : 0ull)); }
  Bytes& f64(double v) {
    const auto bits = std::bit_cast<uint64_t>(v);
    for (int i = 0; i < 8; ++i) {
      u8(static_cast<uint8_t>(bits >> (8 * i)));
    }
    return *this;
  }
  Bytes& text(const std::string& s) {
    var(s.size());
    data += s;
    return *this;
  }
};

uint32_t reference_crc32(const std::string& data) {
  uint32_t crc = ~0u;
  for (const char c : data) {
    crc ^= static_cast<uint8_t>(c);
    for (int k = 0; k < 8; ++k) {
      crc = (crc & 1) != 0 ? 0xEDB88320u ^ (crc >> 1) : crc >> 1;
    }
  }
  return ~crc;
}

std::string finish(Bytes bytes, int64_t last_tick) {
  bytes.u8('Z').zig(last_tick);
  const uint32_t crc = reference_crc32(bytes.data);
  for (int i = 0; i < 4; ++i) {
    bytes.u8(static_cast<uint8_t>(crc >> (8 * i)));
  }
  return bytes.data;
}

}  // namespace

TEST_CASE("The trajectory's CRC-32 is the bitwise one for every length, offset and split",
          "[engine][output][trajectory]") {
  // The writer's crc32 folds whole 16-byte blocks of 64 bytes and more by carry-less
  // multiplication where the processor has it, and takes the rest a byte or eight at a time.
  corsa::RandomStream random(20261127);
  std::string data(4096 + 64, '\0');
  for (char& c : data) c = static_cast<char>(random.uniform_int(0, 255));
  using corsa::engine::detail::trajectory_codec::crc32;
  for (size_t offset = 0; offset < 16; offset += 5) {
    for (size_t length = 0; length <= 700; ++length) {
      const std::string part = data.substr(offset, length);
      REQUIRE(crc32(0, part) == reference_crc32(part));
    }
  }
  const std::string all = data.substr(3, 4096);
  REQUIRE(crc32(0, all) == reference_crc32(all));
  // Updated piece by piece, as the recorder updates it at each flush.
  for (const size_t split : {size_t{1}, size_t{15}, size_t{64}, size_t{100}, size_t{2049}}) {
    const uint32_t first = crc32(0, std::string_view(all).substr(0, split));
    REQUIRE(crc32(first, std::string_view(all).substr(split)) == reference_crc32(all));
  }
  REQUIRE(crc32(0, "123456789") == 0xCBF43926u);  // the check value of CRC-32 (IEEE)
}

TEST_CASE("The CSV export of a binary trajectory is the run's CSV, byte for byte",
          "[engine][output][trajectory]") {
  for (const char* example : {"CutIn.xosc", "FastOvertakeWithReInitialization.xosc",
                              "TrafficJam.xosc", "SynchronizedArrivalToIntersection.xosc"}) {
    INFO(example);
    const Recorded run = record_both(asam(example), 1);
    CHECK(run.csv.size() > 10000);
    CHECK(run.exported == run.csv);
    CHECK(run.binary.size() * 5 < run.csv.size());
  }
  // Entities added, deleted and spawned by traffic; a ghost's run from -2 s (negative ticks,
  // -200 no multiple of 7); every 7th step; another controller.
  for (const char* fixture :
       {"entity_add_delete_visibility.xosc", "traffic_source_sink.xosc", "traffic_swarm.xosc",
        "condition_road.xosc", "controller_follow_ghost.xosc"}) {
    INFO(fixture);
    const Recorded every = record_both(engine_fixture(fixture), 7);
    CHECK(every.exported == every.csv);
    engine::SimulationOptions dynamics;
    dynamics.controller = "dynamics";
    const Recorded other = record_both(engine_fixture(fixture), 1, dynamics);
    CHECK(other.exported == other.csv);
  }
}

TEST_CASE("A ghost restart's ticks run again are in the CSV twice and in the binary file once",
          "[engine][output][trajectory]") {
  // controller_follow_ghost_restart.xosc: the time goes back from 5.01 s to 3.02 s once, and
  // the 200 ticks up to 5.01 s are run (and written to the CSV) again. The binary file keeps the
  // first rows of each tick: its export is the CSV without the rows of times run again.
  for (const int64_t every : {int64_t{1}, int64_t{7}}) {
    INFO(every);
    const Recorded run = record_both(engine_fixture("controller_follow_ghost_restart.xosc"), every);
    std::istringstream lines(run.csv);
    std::string line, first_rows;
    std::getline(lines, line);
    first_rows = line + "\n";
    double latest = -1e300;
    bool kept = false;
    size_t dropped = 0;
    while (std::getline(lines, line)) {
      const double time = std::stod(line.substr(0, line.find(',')));
      kept = time > latest || (time == latest && kept);
      latest = std::max(latest, time);
      if (kept) {
        first_rows += line + "\n";
      } else {
        ++dropped;
      }
    }
    // Three entities (Ego, Other, Ego_ghost) at the recorded ticks among the 200 run again,
    // ticks 302 to 501: all of them, or the 28 multiples of 7 (308 to 497).
    CHECK(dropped == (every == 1 ? 600u : 3u * 28u));
    CHECK(run.exported == first_rows);
  }
}

TEST_CASE("A binary trajectory encoded on the writer thread is the same bytes as on the caller's",
          "[engine][output][trajectory]") {
  // 80 s of long_motorway's 24 vehicles (192,024 rows) fill 24 of the writer's batches, more
  // than it queues; the fixtures add and delete entities, spawn traffic, leave the road and
  // start at negative ticks (a ghost). Every run is cut at 80 s.
  const auto motorway =
      std::filesystem::path(CORSA_SOURCE_DIR) / "tests/bench/scenarios/long_motorway.xosc";
  for (const auto& [scenario, every] : std::vector<std::pair<std::filesystem::path, int64_t>>{
           {motorway, 1},
           {asam("CutIn.xosc"), 1},
           {asam("FastOvertakeWithReInitialization.xosc"), 1},
           {engine_fixture("entity_add_delete_visibility.xosc"), 1},
           {engine_fixture("traffic_swarm.xosc"), 3},
           {engine_fixture("condition_road.xosc"), 1},
           {engine_fixture("controller_follow_ghost.xosc"), 7}}) {
    INFO(scenario.filename().string());
    TempDir dir;
    engine::SimulationOptions options;
    options.duration = 80.0;
    FixtureRun run(scenario, options);
    engine::BinaryTrajectoryRecorder caller(dir.path() / "caller.corsatraj", every,
                                            engine::RecordingThread::kCaller);
    engine::BinaryTrajectoryRecorder writer(dir.path() / "writer.corsatraj", every,
                                            engine::RecordingThread::kWriter);
    engine::BinaryTrajectoryRecorder automatic(dir.path() / "auto.corsatraj", every,
                                               engine::RecordingThread::kAuto);
    run.sim().add_observer(caller);
    run.sim().add_observer(writer);
    run.sim().add_observer(automatic);
    run.run();
    CHECK_FALSE(caller.on_writer_thread());
    CHECK(writer.on_writer_thread());
    // At most 24 entities a tick: too little work for the writer thread to pay.
    CHECK_FALSE(automatic.on_writer_thread());
    caller.finish(run.sim());
    writer.finish(run.sim());
    automatic.finish(run.sim());
    const std::string bytes = read_all(dir.path() / "caller.corsatraj");
    CHECK(bytes.size() > 100);
    const bool same = read_all(dir.path() / "writer.corsatraj") == bytes;  // not printed: MBs
    CHECK(same);
    const bool same_auto = read_all(dir.path() / "auto.corsatraj") == bytes;
    CHECK(same_auto);
  }
  // A recorder destroyed without finish stops its thread and leaves no file.
  TempDir dir;
  {
    FixtureRun run(asam("CutIn.xosc"));
    engine::BinaryTrajectoryRecorder writer(dir.path() / "dropped.corsatraj", 1,
                                            engine::RecordingThread::kWriter);
    run.sim().add_observer(writer);
    run.run();
  }
  CHECK_FALSE(std::filesystem::exists(dir.path() / "dropped.corsatraj"));
}

TEST_CASE(
    "A binary trajectory moved to the writer thread mid-run is the same bytes as on the "
    "caller's",
    "[engine][output][trajectory]") {
  // 300 vehicles on Town04 code about 300 rows a tick: the automatic recorder moves to its
  // writer thread after its first window of ticks, with names and roads already written.
  TempDir dir;
  write_all(dir.path() / "town04_npc.xosc",
            "<?xml version=\"1.0\"?><OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
            "date=\"2026-01-01T00:00:00\" description=\"npc\" author=\"Corsa\"/>"
            "<ParameterDeclarations/><CatalogLocations/><RoadNetwork><LogicFile filepath=\"" +
                (std::filesystem::path(CORSA_SHARED_DIR) / "data/xodr/Town04.xodr").string() +
                "\"/></RoadNetwork><Entities/><Storyboard><Init><Actions/></Init><StopTrigger/>"
                "</Storyboard></OpenSCENARIO>");
  engine::SimulationOptions options;
  options.duration = 8.0;
  options.seed = 3;
  options.npc.vehicles = 300;
  options.npc.pedestrians = 20;
  FixtureRun run(dir.path() / "town04_npc.xosc", options);
  engine::BinaryTrajectoryRecorder caller(dir.path() / "caller.corsatraj", 1,
                                          engine::RecordingThread::kCaller);
  engine::BinaryTrajectoryRecorder automatic(dir.path() / "auto.corsatraj", 1,
                                             engine::RecordingThread::kAuto);
  run.sim().add_observer(caller);
  run.sim().add_observer(automatic);
  run.run();
  CHECK(automatic.on_writer_thread());
  caller.finish(run.sim());
  automatic.finish(run.sim());
  const std::string bytes = read_all(dir.path() / "caller.corsatraj");
  CHECK(bytes.size() > 100000);
  const bool same = read_all(dir.path() / "auto.corsatraj") == bytes;  // not printed: MBs
  CHECK(same);
}

namespace {

// Every tick's rows made afresh (TrajectoryRecorder::append_rows), as a recorder that made
// every row anew would write them.
class FreshRows final : public engine::SimulationObserver {
 public:
  void on_step(const engine::Simulation& sim) override {
    engine::TrajectoryRecorder::append_rows(sim, text);
  }
  std::string text = engine::kTrajectoryHeader;
};

}  // namespace

namespace {

// Compares, after every step, each entity's state read through Simulation::states with the one
// Simulation::state gives.
class StatesAsStored final : public engine::SimulationObserver {
 public:
  void on_step(const engine::Simulation& sim) override {
    const engine::EntityStates states = sim.states();
    counts_match = counts_match && states.size() == sim.entity_count();
    for (size_t i = 0; i < states.size(); ++i) {
      same_objects = same_objects && &states[i] == &sim.state(i);
    }
    most = std::max(most, states.size());
  }
  bool counts_match = true;
  bool same_objects = true;
  size_t most = 0;
};

}  // namespace

TEST_CASE("The states as the run keeps them are the entities' states, as entities are added",
          "[engine][output][trajectory]") {
  // traffic_swarm spawns vehicles during the run, so the records move as they grow.
  FixtureRun run(engine_fixture("traffic_swarm.xosc"));
  StatesAsStored check;
  run.sim().add_observer(check);
  run.run();
  CHECK(check.counts_match);
  CHECK(check.same_objects);
  CHECK(check.most > 3);
}

TEST_CASE("Rows of entities that stand still are the bytes of rows made afresh, in both files",
          "[engine][output][trajectory]") {
  // TrafficJam's vehicles stand from the start; the fixtures' entities stop, appear, leave,
  // leave the road and are spawned by traffic.
  const std::vector<std::filesystem::path> scenarios = {
      asam("TrafficJam.xosc"), engine_fixture("entity_add_delete_visibility.xosc"),
      engine_fixture("traffic_source_sink.xosc"), engine_fixture("condition_road.xosc")};
  for (const auto& scenario : scenarios) {
    INFO(scenario.filename().string());
    const Recorded run = record_both(scenario, 1);
    FixtureRun fresh(scenario);
    FreshRows rows;
    fresh.sim().add_observer(rows);
    fresh.run();
    CHECK(run.csv.size() > 1000);
    CHECK(run.csv == rows.text);
    CHECK(run.exported == rows.text);
  }
}

TEST_CASE("A binary trajectory's rows are the numbers the CSV rows read back as",
          "[engine][output][trajectory]") {
  TempDir dir;
  engine::RunOptions options;
  options.scenario = engine_fixture("condition_road.xosc");
  options.record = dir.path() / "run.corsatraj";
  Diagnostics diagnostics;
  engine::run_scenario(options, diagnostics);
  engine::TrajectoryReader reader(dir.path() / "run.corsatraj");
  std::istringstream csv(engine::trajectory_csv_of(dir.path() / "run.corsatraj"));
  std::string line;
  std::getline(csv, line);  // header
  engine::TrajectoryFrame frame;
  size_t rows = 0;
  while (reader.next(frame)) {
    for (const engine::TrajectoryRow& row : frame.rows) {
      REQUIRE(std::getline(csv, line));
      const auto f = split(line, ',');
      REQUIRE(f.size() == 13);
      CHECK(parse_double(f[0]) == frame.time);
      CHECK(f[1] == reader.entity_name(row.entity));
      CHECK(parse_double(f[2]) == row.x);
      CHECK(parse_double(f[3]) == row.y);
      CHECK(parse_double(f[5]) == row.h);
      CHECK(parse_double(f[8]) == row.speed);
      CHECK(f[9].empty() == !row.on_road);
      if (row.on_road) {
        CHECK(f[9] == reader.road_id(row.road));
        CHECK(f[10] == std::to_string(row.lane));
        CHECK(parse_double(f[11]) == row.s);
        CHECK(parse_double(f[12]) == row.t);
      }
      ++rows;
    }
  }
  CHECK_FALSE(std::getline(csv, line));
  CHECK(rows > 1000);
  CHECK(reader.frame_count() == static_cast<size_t>(reader.last_tick() + 1));
}

TEST_CASE("Entities standing still or driving straight at a steady speed cost nothing",
          "[engine][output][trajectory]") {
  // The ASAM TrafficJam: vehicles standing for the whole run, and an ego at a steady speed on a
  // straight road.
  const Recorded jam = record_both(asam("TrafficJam.xosc"), 1);
  CHECK(jam.exported == jam.csv);
  // Eight entities over 1,001 ticks: a few bytes per entity for the run.
  CHECK(jam.binary.size() < 1000);
}

namespace {

// A standing entity's row whose numbers move below their last decimal from tick to tick, by
// `wobble` (0: exactly the first tick's numbers).
engine::detail::TrajectoryRowCopy wobbling_row(int64_t tick, double wobble) {
  const double sign = tick % 2 == 0 ? 1.0 : -1.0;
  engine::detail::TrajectoryRowCopy row;
  row.placed = true;
  row.on_road = true;
  row.road = 0;
  row.lane = -2;
  row.values = {1234.5678 + sign * wobble * 1e-7,  // x, m: 1e-13 m at most
                -87.25 + static_cast<double>(tick % 3) * wobble * 1e-7,
                0.0,
                0.75 + sign * wobble * 1e-10,  // h, rad: below a nrad
                0.0,
                0.0,
                12.5 - wobble * 1e-8,  // speed, m/s
                310.125 + sign * wobble * 1e-7,
                -1.75 + wobble * 1e-7};
  return row;
}

std::string encode_rows(const std::filesystem::path& path,
                        const std::vector<engine::detail::TrajectoryRowCopy>& rows) {
  const std::string road = "7";
  engine::detail::TrajectoryEncoder encoder(path, 1);
  encoder.name_entity("car");
  encoder.name_road(0, &road);
  for (size_t tick = 0; tick < rows.size(); ++tick) {
    const engine::detail::TrajectoryRowCopy* row = &rows[tick];
    encoder.record(0.01, {static_cast<int64_t>(tick), static_cast<double>(tick) / 100.0, 1}, row);
  }
  encoder.finish(static_cast<int64_t>(rows.size()) - 1);
  return read_all(path);
}

}  // namespace

TEST_CASE("Numbers that move only below their last decimal are stored as the numbers they print",
          "[engine][output][trajectory]") {
  TempDir dir;
  std::vector<engine::detail::TrajectoryRowCopy> still;
  std::vector<engine::detail::TrajectoryRowCopy> wobbling;
  for (int64_t tick = 0; tick < 300; ++tick) {
    still.push_back(wobbling_row(tick, 0.0));
    wobbling.push_back(wobbling_row(tick, 1e-6 * static_cast<double>(1 + tick % 5)));
  }
  // The same printed numbers at every tick: the same bytes as a row that never changes (one
  // record, at the first tick).
  const std::string bytes = encode_rows(dir.path() / "still.corsatraj", still);
  CHECK(encode_rows(dir.path() / "wobbling.corsatraj", wobbling) == bytes);

  // Numbers that wobble across the half of their last decimal print as the one or the other:
  // each row reads back as its own numbers rounded to their decimals.
  std::vector<engine::detail::TrajectoryRowCopy> straddling;
  for (int64_t tick = 0; tick < 300; ++tick) {
    engine::detail::TrajectoryRowCopy row = wobbling_row(tick, 0.0);
    const double sign = (tick / 3) % 2 == 0 ? 1.0 : -1.0;
    row.values[engine::detail::kFieldX] = 2.0000005 + sign * 1e-12;
    row.values[engine::detail::kFieldH] = -0.0000000005 + sign * 1e-15;
    straddling.push_back(row);
  }
  encode_rows(dir.path() / "straddling.corsatraj", straddling);
  engine::TrajectoryReader reader(dir.path() / "straddling.corsatraj");
  engine::TrajectoryFrame frame;
  size_t ticks = 0;
  std::vector<double> xs;
  while (reader.next(frame)) {
    REQUIRE(frame.rows.size() == 1);
    const engine::detail::TrajectoryRowCopy& row = straddling.at(ticks++);
    const auto x = engine::detail::scale_decimal<6>(row.values[engine::detail::kFieldX]);
    const auto h = engine::detail::scale_decimal<9>(row.values[engine::detail::kFieldH]);
    CHECK(frame.rows[0].x == static_cast<double>(x.units) / 1e6);
    CHECK(frame.rows[0].h == static_cast<double>(h.units) / 1e9);
    xs.push_back(frame.rows[0].x);
  }
  CHECK(ticks == straddling.size());
  // Both sides of the half occur.
  CHECK(std::count(xs.begin(), xs.end(), 2.000001) > 100);
  CHECK(std::count(xs.begin(), xs.end(), 2.0) > 100);
}

namespace {

// Entities whose rows stand, wobble below their last decimals, cross the half of one, move,
// change road or lane, leave the road, leave and come back, at random from tick to tick (a
// stream of its own, the same at every run): the encoder's skip pass, its test below the
// decimals and its coding all meet every kind of row, in any order of kinds among entities.
struct MixedRows {
  static constexpr size_t kEntities = 9;
  static constexpr int64_t kTicks = 3000;
  std::vector<std::vector<engine::EntityState>> ticks;  ///< every entity's state at each tick

  MixedRows() {
    RandomStream rng = RandomStream::derive(11, "mixed rows");
    std::vector<engine::EntityState> states(kEntities);
    for (size_t e = 0; e < kEntities; ++e) {
      engine::EntityState& state = states[e];
      state.placed = e != 3;  // entity 3 appears later
      state.pose = {100.0 + 10.0 * static_cast<double>(e), -20.0, 1.5, 0.25, 0.0, 0.0};
      state.speed = e % 2 == 0 ? 0.0 : 5.0;
      if (e != 5) {  // entity 5 starts off the road
        state.road = engine::RoadCoordinates{static_cast<uint32_t>(e % 2), 0, -1, 40.0, -1.75};
      }
    }
    for (int64_t tick = 0; tick < kTicks; ++tick) {
      for (engine::EntityState& state : states) {
        change(rng, state);
      }
      ticks.push_back(states);
    }
  }

  // A value moved by an ulp: below its last decimal unless it lies at the half of one.
  static double wobble(double value) { return std::nextafter(value, value > 0 ? 1e300 : -1e300); }

  // Field f of `state` (RowField order; s and t only on a road).
  static double* field(engine::EntityState& state, int f) {
    double* fields[] = {&state.pose.x, &state.pose.y, &state.pose.z, &state.pose.h,
                        &state.pose.p, &state.pose.r, &state.speed};
    if (f == engine::detail::kFieldS) {
      return &state.road->s;
    }
    if (f == engine::detail::kFieldT) {
      return &state.road->t;
    }
    return fields[f];
  }

  static void change(RandomStream& rng, engine::EntityState& state) {
    const uint64_t kind = rng.next_u64() % 100;
    const int fields = state.road ? engine::detail::kRowFields : engine::detail::kFieldS;
    const int f = static_cast<int>(rng.next_u64() % static_cast<uint64_t>(fields));
    const bool angle = f >= engine::detail::kFieldH && f <= engine::detail::kFieldR;
    const double unit = angle ? 1e-9 : 1e-6;
    if (kind < 55) {
      return;  // stands
    }
    if (kind < 75) {
      double& value = *field(state, f);
      value = wobble(value);
    } else if (kind < 83) {
      // Half a unit off its decimals, give or take an ulp or two: prints as one or the other.
      double& value = *field(state, f);
      value = (std::round(value / unit) + (rng.next_u64() % 2 == 0 ? 0.5 : -0.5)) * unit;
      for (uint64_t k = rng.next_u64() % 3; k > 0; --k) {
        value = wobble(value);
      }
    } else if (kind < 93) {
      *field(state, f) +=
          static_cast<double>(static_cast<int64_t>(rng.next_u64() % 2001) - 1000) * unit;
    } else if (kind < 96) {
      if (state.road) {
        state.road->lane += rng.next_u64() % 2 == 0 ? 1 : -1;
        if (rng.next_u64() % 2 == 0) {
          state.road->road ^= 1;
        }
      }
    } else if (kind < 98) {
      if (state.road) {
        state.road.reset();
      } else {
        state.road = engine::RoadCoordinates{2, 0, 1, 5.0, 0.5};
      }
    } else {
      state.placed = !state.placed;
    }
  }
};

}  // namespace

TEST_CASE("Rows that stand, wobble below their decimals, move and leave read back as they print",
          "[engine][output][trajectory]") {
  const MixedRows mixed;
  TempDir dir;
  const std::vector<std::string> roads = {"r0", "r1", "r2", "r3"};  // road ^ 1 of 2 is 3
  // The rows read straight from the states (as on the run's thread) and from their copies (as
  // on the writer thread).
  auto encode = [&](const std::filesystem::path& path, bool copies) {
    engine::detail::TrajectoryEncoder encoder(path, 1);
    for (size_t e = 0; e < MixedRows::kEntities; ++e) {
      // (Appended, not "e" + to_string: GCC 12 reports -Warray-bounds on that operator+ inlined
      // here, the false positive of the family of GCC bug 105651.)
      std::string name = "e";
      name += std::to_string(e);
      encoder.name_entity(name);
    }
    for (uint32_t r = 0; r < roads.size(); ++r) {
      encoder.name_road(r, &roads[r]);
    }
    std::vector<engine::detail::TrajectoryRowCopy> rows(MixedRows::kEntities);
    for (int64_t tick = 0; tick < MixedRows::kTicks; ++tick) {
      const auto& states = mixed.ticks[static_cast<size_t>(tick)];
      const engine::detail::TickRowsHead head{tick, static_cast<double>(tick) / 100.0,
                                              static_cast<uint32_t>(states.size())};
      if (copies) {
        for (size_t e = 0; e < states.size(); ++e) {
          engine::detail::copy_row(rows[e], states[e]);
        }
        const engine::detail::TrajectoryRowCopy* first = rows.data();
        encoder.record(0.01, head, first);
      } else {
        const engine::detail::EntityStateRows from_states{
            engine::EntityStates(states.data(), states.size(), sizeof(engine::EntityState)),
            nullptr, engine::EntityStateChanges{}};
        encoder.record(0.01, head, from_states);
      }
    }
    encoder.finish(MixedRows::kTicks - 1);
    return read_all(path);
  };
  const std::string bytes = encode(dir.path() / "states.corsatraj", false);
  const bool same = encode(dir.path() / "copies.corsatraj", true) == bytes;
  CHECK(same);

  engine::TrajectoryReader reader(dir.path() / "states.corsatraj");
  engine::TrajectoryFrame frame;
  int64_t tick = 0;
  size_t rows = 0;
  size_t wrong = 0;
  using engine::detail::field_value;
  using engine::detail::scale_decimal;
  while (reader.next(frame)) {
    REQUIRE(frame.tick == tick);
    const auto& states = mixed.ticks[static_cast<size_t>(tick)];
    size_t k = 0;
    for (uint32_t e = 0; e < states.size(); ++e) {
      const engine::EntityState& state = states[e];
      if (!state.placed) {
        continue;
      }
      REQUIRE(k < frame.rows.size());
      const engine::TrajectoryRow& row = frame.rows[k++];
      const auto length = [](double v) { return field_value(scale_decimal<6>(v), 6); };
      const auto angle = [](double v) { return field_value(scale_decimal<9>(v), 9); };
      bool right = row.entity == e && row.x == length(state.pose.x) &&
                   row.y == length(state.pose.y) && row.z == length(state.pose.z) &&
                   row.h == angle(state.pose.h) && row.p == angle(state.pose.p) &&
                   row.r == angle(state.pose.r) && row.speed == length(state.speed) &&
                   row.on_road == state.road.has_value();
      if (right && state.road) {
        right = reader.road_id(row.road) == roads[state.road->road] &&
                row.lane == state.road->lane && row.s == length(state.road->s) &&
                row.t == length(state.road->t);
      }
      wrong += right ? 0 : 1;
      ++rows;
    }
    CHECK(k == frame.rows.size());
    ++tick;
  }
  CHECK(tick == MixedRows::kTicks);
  CHECK(rows > 10000);
  CHECK(wrong == 0);
}

TEST_CASE("A binary trajectory written from the documented format reads as documented",
          "[engine][output][trajectory]") {
  TempDir dir;
  Bytes b;
  b.data = "CORSATRJ";
  b.u8(1).f64(0.01).var(100).var(5).zig(0);
  b.u8('E').var(0).text("Car").u8('E').var(1).text("Ghost");
  b.u8('R').var(3).text("main");
  // Tick 0: Car appears on road 3 lane -1 at x = 1 m, y = -2.5 m, s = 10 m, t = -1.75 m,
  // speed 20 m/s (units of 1e-6; angles 1e-9).
  b.u8('F').zig(0);
  const uint32_t fields = (1u << 0) | (1u << 1) | (1u << 6) | (1u << 7) | (1u << 8);
  b.var(1).var(fields | (1u << 9) | (1u << 10) | (1u << 11));
  b.var(3 + 1).zig(-1);  // road, lane
  b.zig(1'000'000).zig(-2'500'000).zig(20'000'000).zig(10'000'000).zig(-1'750'000);
  b.var(0);
  // Tick 5: nothing recorded (Car as predicted: standing). Tick 10: Car moves 0.2 m along x and
  // s; Ghost appears off the road with a raw x (NaN) and y = 3 m.
  b.u8('F').zig(10);
  b.var(1).var((1u << 0) | (1u << 7)).zig(200'000).zig(200'000);
  b.var(1).var((1u << 1) | (1u << 11) | (1u << 12)).var(1u << 0);
  b.f64(std::nan("")).zig(3'000'000);
  b.var(0);
  // Tick 15 is the last (on the interval): Car keeps moving as predicted.
  write_all(dir.path() / "hand.corsatraj", finish(b, 15));

  engine::TrajectoryReader reader(dir.path() / "hand.corsatraj");
  CHECK(reader.frame_count() == 4);
  CHECK(reader.entity_count() == 2);
  CHECK(reader.road_id(3) == "main");
  engine::TrajectoryFrame frame;
  REQUIRE(reader.next(frame));
  CHECK(frame.tick == 0);
  REQUIRE(frame.rows.size() == 1);
  CHECK(frame.rows[0].x == 1.0);
  CHECK(frame.rows[0].lane == -1);
  REQUIRE(reader.next(frame));
  CHECK(frame.tick == 5);
  CHECK(frame.time == 0.05);
  CHECK(frame.rows[0].x == 1.0);  // the first change is none
  REQUIRE(reader.next(frame));
  CHECK(frame.tick == 10);
  REQUIRE(frame.rows.size() == 2);
  CHECK(frame.rows[0].x == 1.2);
  CHECK(frame.rows[0].s == 10.2);
  CHECK(std::isnan(frame.rows[1].x));
  CHECK(frame.rows[1].y == 3.0);
  CHECK_FALSE(frame.rows[1].on_road);
  REQUIRE(reader.next(frame));
  CHECK(frame.tick == 15);
  CHECK(frame.rows[0].x == 1.4);  // repeats the last change
  CHECK(frame.rows[0].s == 10.4);
  CHECK(frame.rows[1].y == 3.0);
  CHECK_FALSE(reader.next(frame));
  const std::string csv = engine::trajectory_csv_of(dir.path() / "hand.corsatraj");
  CHECK_THAT(csv, Catch::Contains("0.15,Car,1.4,-2.5,0,0,0,0,20,main,-1,10.4,-1.75\n"));
  CHECK_THAT(csv, Catch::Contains("0.1,Ghost,nan,3,0,0,0,0,0,,,,\n"));
}

TEST_CASE("A damaged binary trajectory is an error naming the file, never a crash",
          "[engine][output][trajectory][errors]") {
  TempDir dir;
  engine::RunOptions options;
  options.scenario = engine_fixture("traffic_source_sink.xosc");
  options.record = dir.path() / "good.corsatraj";
  Diagnostics diagnostics;
  engine::run_scenario(options, diagnostics);
  const std::string good = read_all(dir.path() / "good.corsatraj");
  REQUIRE(good.size() > 100);
  const auto path = dir.path() / "bad.corsatraj";
  const auto fails = [&](const std::string& bytes) {
    write_all(path, bytes);
    try {
      engine::trajectory_csv_of(path);
    } catch (const InputError& error) {
      return error.diagnostic().file == path.string();
    }
    return false;
  };
  CHECK(fails(""));
  CHECK(fails("CORSATRJ"));
  CHECK(fails("time,entity,x\n"));
  // Every truncation.
  for (size_t n = 0; n < good.size(); n += std::max<size_t>(1, good.size() / 400)) {
    INFO("truncated to " << n);
    CHECK(fails(good.substr(0, n)));
  }
  // Bytes changed anywhere: the checksum or the structure says so.
  RandomStream random(3);
  for (int i = 0; i < 300; ++i) {
    std::string bad = good;
    const auto at =
        static_cast<size_t>(random.uniform_int(0, static_cast<int64_t>(bad.size()) - 1));
    bad[at] = static_cast<char>(bad[at] ^ (1 + random.uniform_int(0, 254)));
    INFO("byte " << at);
    CHECK(fails(bad));
  }
  // And the command line says it with exit code 2, writing nothing.
  write_all(path, good.substr(0, good.size() / 2));
  const ProcessResult result =
      run_corsa({"record", "export", path.string(), "-o", (dir.path() / "out.csv").string()});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.err, Catch::Contains("bad.corsatraj"));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "out.csv"));
}

TEST_CASE("corsa record export writes the CSV corsa run --record writes", "[engine][cli]") {
  TempDir dir;
  const auto scenario = asam("CutIn.xosc").string();
  const auto csv = (dir.path() / "run.csv").string();
  const auto bin = (dir.path() / "run.corsatraj").string();
  const auto out = (dir.path() / "export" / "run.csv").string();
  REQUIRE(run_corsa({"run", scenario, "--quiet", "--record", csv}).exit_code == 0);
  REQUIRE(run_corsa({"run", scenario, "--quiet", "--record", bin}).exit_code == 0);
  const ProcessResult exported = run_corsa({"record", "export", bin, "-o", out});
  CHECK(exported.exit_code == 0);
  CHECK(read_all(out) == read_all(csv));
  const ProcessResult info = run_corsa({"record", "info", bin});
  CHECK(info.exit_code == 0);
  CHECK_THAT(info.out, Catch::Contains("entities:      3"));
}

TEST_CASE("A standing entity among moving ones records its move after many unchanged ticks",
          "[engine][output][trajectory]") {
  // Entities 0 and 1 move at every tick, so that the encoder codes every row in one pass (the
  // pass for moving rows, which skips a steady row by its test); entity 2 stands, its count of
  // writes unchanged, for 520 ticks, and then moves once (its count moved). Read with the counts
  // and without them, the files are the same bytes, and entity 2's row at the tick of its move is
  // the moved one.
  constexpr int64_t kTicks = 800;
  constexpr int64_t kMove = 520;
  TempDir dir;
  auto encode = [&](const std::filesystem::path& path, bool counted) {
    engine::detail::TrajectoryEncoder encoder(path, 1);
    for (const char* name : {"a", "b", "still"}) {
      encoder.name_entity(name);
    }
    std::vector<engine::EntityState> states(3);
    std::vector<uint32_t> counts(3, 0);
    for (auto& state : states) {
      state.placed = true;
      state.pose.y = 2.0;
    }
    for (int64_t tick = 0; tick < kTicks; ++tick) {
      for (size_t e = 0; e < 2; ++e) {
        states[e].pose.x = 0.37 * static_cast<double>(tick * tick) + static_cast<double>(e);
        states[e].speed = 0.74 * static_cast<double>(tick);
        ++counts[e];
      }
      if (tick == kMove) {
        states[2].pose.x = 12.345678;
        states[2].pose.h = 0.5;
        ++counts[2];
      }
      const engine::detail::EntityStateRows rows{
          engine::EntityStates(states.data(), states.size(), sizeof(engine::EntityState)), nullptr,
          counted ? engine::EntityStateChanges(counts.data(), counts.size(), sizeof(uint32_t))
                  : engine::EntityStateChanges{}};
      encoder.record(0.01, {tick, static_cast<double>(tick) / 100.0, 3}, rows);
    }
    encoder.finish(kTicks - 1);
    return read_all(path);
  };
  const std::string bytes = encode(dir.path() / "counted.corsatraj", true);
  const bool same = encode(dir.path() / "tested.corsatraj", false) == bytes;
  CHECK(same);

  engine::TrajectoryReader reader(dir.path() / "counted.corsatraj");
  engine::TrajectoryFrame frame;
  size_t moved_rows = 0;
  while (reader.next(frame)) {
    REQUIRE(frame.rows.size() == 3);
    const engine::TrajectoryRow& still = frame.rows[2];
    CHECK(still.entity == 2);
    if (frame.tick < kMove) {
      CHECK(still.x == 0.0);
      CHECK(still.h == 0.0);
    } else {
      CHECK(still.x == 12.345678);
      CHECK(still.h == 0.5);
      ++moved_rows;
    }
    CHECK(still.y == 2.0);
  }
  CHECK(moved_rows == static_cast<size_t>(kTicks - kMove));
}

}  // namespace corsa::test
