// Every write of an entity's state goes through EntityMotion::write_state, which counts it
// (state/entity.h; Simulation::state_changes gives the counts): while an entity's count stays,
// its state is the same, bit for bit. The binary recorder skips an entity whose count has not
// moved since its row last passed, and the memos of what was computed from a state pass over
// it, so a write that does not count would leave a wrong row in the file or a stale result.
// These tests run every focused scenario and ASAM example, in both semantics, and check after
// every step that no state changed while its count stayed; and that the recordings of scenarios
// that teleport, change lanes, tow trailers, hide, add and delete entities are the same bytes
// read with the counts (the caller's thread) and without them (the writer thread's copies).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/engine/trajectory_file.h"
#include "engine_fixture.h"
#include "state/sim_state.h"
#include "temp_dir.h"

namespace {

using corsa::test::asam;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;
namespace engine = corsa::engine;

// After every step: each entity whose count of writes is the one of the step before holds the
// state of the step before, bit for bit.
class CountedWrites final : public engine::SimulationObserver {
 public:
  void on_step(const engine::Simulation& sim) override {
    const engine::EntityStates states = sim.states();
    const engine::EntityStateChanges changes = sim.state_changes();
    REQUIRE(changes.size() == states.size());
    for (size_t i = 0; i < states.size(); ++i) {
      if (i < last_.size() && changes[i] == counts_[i]) {
        ++unchanged_;
        if (!engine::detail::same_bits(states[i], last_[i]) && first_miss_.empty()) {
          std::ostringstream out;
          out << "entity " << sim.entity(i).name << " at tick " << sim.tick()
              << ": its state changed while its count stayed " << counts_[i];
          first_miss_ = out.str();
        }
      } else if (i < last_.size()) {
        ++changed_;
      }
    }
    last_.assign(states.size(), engine::EntityState{});
    counts_.assign(states.size(), 0);
    for (size_t i = 0; i < states.size(); ++i) {
      last_[i] = states[i];
      counts_[i] = changes[i];
    }
  }

  std::string first_miss_;
  uint64_t unchanged_ = 0;  ///< entity-steps with the same count
  uint64_t changed_ = 0;    ///< entity-steps with another count

 private:
  std::vector<engine::EntityState> last_;
  std::vector<uint32_t> counts_;
};

std::vector<std::filesystem::path> scenarios_in(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".xosc") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("No entity's state changes in a step while its count of writes stays",
          "[engine][state]") {
  std::vector<std::filesystem::path> files = scenarios_in(engine_fixture(""));
  const std::vector<std::filesystem::path> examples = scenarios_in(asam(""));
  files.insert(files.end(), examples.begin(), examples.end());
  int runs = 0;
  uint64_t unchanged = 0, changed = 0;
  for (const auto semantics : {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    for (const auto& file : files) {
      INFO(file.filename().string());
      engine::SimulationOptions options;
      options.duration = 60.0;
      options.semantics = semantics;
      std::unique_ptr<FixtureRun> run;
      try {
        run = std::make_unique<FixtureRun>(file, options);
      } catch (const std::exception&) {
        continue;  // a file that does not load (a catalog, an error fixture) runs nothing
      }
      CountedWrites check;
      run->sim().add_observer(check);
      try {
        run->run();
      } catch (const std::exception&) {
        // A run that stops on an error (the error fixtures) was checked up to there.
      }
      INFO(check.first_miss_);
      CHECK(check.first_miss_.empty());
      ++runs;
      unchanged += check.unchanged_;
      changed += check.changed_;
    }
  }
  // Most fixtures and examples run, and both cases are met many times.
  CHECK(runs > 200);
  CHECK(unchanged > 100000);
  CHECK(changed > 100000);
}

TEST_CASE("Recordings read with the counts of writes are the bytes of recordings read without",
          "[engine][output][trajectory]") {
  // The caller's thread skips an entity whose count has not moved; the writer thread reads
  // copies of every row, without counts, and tests each. Teleports (in place, to positions, at a
  // lane change, at the end of the road), lane changes and offsets, trailers, visibility,
  // entities added and deleted, ghosts, traffic sources and sinks.
  for (const char* name :
       {"action_teleport_positions.xosc", "semantics_teleport_in_place.xosc",
        "semantics_teleport_and_lane_change.xosc", "motion_end_of_road_teleport.xosc",
        "action_lane_change.xosc", "action_lane_offset.xosc", "compat_trailer.xosc",
        "compat_trailer_esmini_form.xosc", "visibility_sensor_refs.xosc",
        "entity_add_delete_visibility.xosc", "controller_follow_ghost_teleport.xosc",
        "controller_follow_ghost_restart.xosc", "traffic_source_sink.xosc",
        "action_follow_trajectory.xosc", "semantics_stand_still_creep.xosc"}) {
    INFO(name);
    corsa::test::TempDir dir;
    FixtureRun run(engine_fixture(name));
    engine::BinaryTrajectoryRecorder caller(dir.path() / "caller.corsatraj", 1,
                                            engine::RecordingThread::kCaller);
    engine::BinaryTrajectoryRecorder writer(dir.path() / "writer.corsatraj", 1,
                                            engine::RecordingThread::kWriter);
    run.sim().add_observer(caller);
    run.sim().add_observer(writer);
    run.run();
    caller.finish(run.sim());
    writer.finish(run.sim());
    const std::string bytes = read_all(dir.path() / "caller.corsatraj");
    CHECK_FALSE(bytes.empty());  // written (visibility_sensor_refs: 88 bytes)
    const bool same = read_all(dir.path() / "writer.corsatraj") == bytes;
    CHECK(same);
  }
}
