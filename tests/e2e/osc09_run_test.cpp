// `corsa run` on OpenSCENARIO 0.9 drafts (tests/xosc/fixtures/osc09, modelled on esmini's 0.9
// examples): read as 1.0 by the 0.9-to-1.0 mapping, each runs to its stop trigger.

#include <algorithm>
#include <cmath>

#include "csv_compare.h"
#include "recorded_run.h"
#include "run_corsa.h"

namespace corsa::test {
namespace {

const std::string kDraftSynchronizeQuit = "tests/xosc/fixtures/osc09/synchronize_quit.xosc";
const std::string kDraftCutIn = "tests/xosc/fixtures/osc09/cut_in.xosc";
const std::string kDraftSignalsTraffic = "tests/xosc/fixtures/osc09/signals_traffic.xosc";
const std::string kDraftWarning =
    "warning: OpenSCENARIO 0.9 draft (read as 1.0 by the 0.9-to-1.0 mapping: ";

size_t draft_count_of(const std::string& text, const std::string& needle) {
  size_t count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

TEST_CASE("corsa run reads a 0.9 draft's route position, EXT_Synchronize, Meeting and EXT_Quit",
          "[e2e][run][osc09]") {
  const RecordedRun run = run_recorded(kDraftSynchronizeQuit);
  const ProcessResult& result = run.result;
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK(draft_count_of(result.err, "OpenSCENARIO 0.9") == 1);
  CHECK(result.err.find(kDraftSynchronizeQuit + ":7: " + kDraftWarning) != std::string::npos);
  CHECK(result.err.find("EXT_Synchronize, TargetSpeed") != std::string::npos);
  // Ego (20 m/s from s = 50) reaches s = 250 at t = 10: both followers arrive with it, the
  // synchronization ends, and EXT_Quit's event (2 s after that end) stops the run.
  CHECK(result.err.find("Routing, FollowRoute, Route, Position, LaneCoord") != std::string::npos);
  const auto& rows = run.rows;
  // Ego starts at pathS = 50 of its route, which runs along lane -1 from s = 0.
  CHECK(row_at(rows, "Ego", 0.0).x == Approx(50.0).margin(0.01));
  CHECK(row_at(rows, "Ego", 0.0).lane == -1);
  const TrajectoryRow& ego = row_at(rows, "Ego", 10.0);
  CHECK(ego.x == Approx(250.0).margin(0.01));
  CHECK(row_at(rows, "Synced", 10.0).x == Approx(250.0).margin(0.5));
  CHECK(row_at(rows, "Synced", 10.0).lane == -2);
  CHECK(row_at(rows, "Met", 10.0).x == Approx(250.0).margin(0.5));
  CHECK(row_at(rows, "Met", 10.0).lane == -3);
  const std::string& transitions = run.log;
  CHECK(transitions.find("10.02,event,SyncStory::SyncAct::SyncSequence::SyncManeuver::SyncEvent,"
                         "endTransition") != std::string::npos);
  CHECK(transitions.find("12.02,storyboard,,stopTransition") != std::string::npos);
  CHECK(rows.back().time == Approx(12.02));
}

TEST_CASE("corsa run reads a 0.9 cut-in: $owner, relative targets and the Storyboard's End",
          "[e2e][run][osc09]") {
  const RecordedRun run = run_recorded(kDraftCutIn);
  const ProcessResult& result = run.result;
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK(draft_count_of(result.err, "warning:") == 1);
  CHECK(result.err.find(kDraftCutIn + ":6: " + kDraftWarning) != std::string::npos);
  // The owner drives at 1.2 x 20 m/s from 50 m behind: 20 m ahead at t = 17.5, then changes
  // into Ego's lane in 2 s; the End stops the run 1 s later.
  const std::string& transitions = run.log;
  CHECK(transitions.find("17.51,event,CutInStory::CutInAct::CutInSequence::CutInManeuver::"
                         "CutInEvent,startTransition") != std::string::npos);
  CHECK(transitions.find("20.51,storyboard,,stopTransition") != std::string::npos);
  const auto& rows = run.rows;
  CHECK(row_at(rows, "Overtaker", 17.0).lane == -2);
  CHECK(row_at(rows, "Overtaker", 20.0).lane == -1);
  CHECK(row_at(rows, "Overtaker", 20.0).speed == Approx(24.0));
}

TEST_CASE(
    "corsa run performs a 0.9.1 file's Signals, Selection, ByCondition actors, "
    "Infrastructure, Traffic and UserDefined actions",
    "[e2e][run][osc09]") {
  const RecordedRun run = run_recorded(kDraftSignalsTraffic);
  const ProcessResult& result = run.result;
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  const std::string& err = result.err;
  const std::string at = kDraftSignalsTraffic + ":";
  CHECK(err.find(at + "12: " + kDraftWarning) != std::string::npos);
  for (const char* form : {"Signals", "Selection", "Traffic, Source", "ByCondition",
                           "Infrastructure, SetController", "SetState, UserDefined, Command"}) {
    CHECK(err.find(form) != std::string::npos);
  }
  CHECK(err.find(at + "61: warning: 0.9 VehicleDistribution category=\"lorry\" is no 1.0 "
                      "vehicle category (read as car") != std::string::npos);
  CHECK(err.find(at + "63: warning: 0.9 DriverDistribution names drivers (DefaultDriver)") !=
        std::string::npos);
  CHECK(err.find(at + "183: warning: 0.9 UserDefined Command \"corsa:note\" has no type") !=
        std::string::npos);
  // The command was given: the engine found no handler for its type.
  CHECK(err.find("CustomCommandAction type 'corsa:note' has no handler in this run") !=
        std::string::npos);
  const std::string& transitions = run.log;
  // SetController puts Main in its stop phase at 2 s (its own phases would at 5 s); only Ego of
  // the selection Cars is faster than 15 m/s, so only Ego brakes: 20 m/s at 5 m/s^2, 4 s.
  const std::string maneuver = "SignalStory::SignalAct::Infrastructure::SignalManeuver::";
  CHECK(transitions.find("2.01,event," + maneuver + "ForceStop,startTransition") !=
        std::string::npos);
  CHECK(transitions.find("2.02,event,SignalStory::SignalAct::Brakers::BrakeManeuver::StopAtRed,"
                         "startTransition") != std::string::npos);
  CHECK(transitions.find("3.01,event," + maneuver + "SeenFlash,startTransition") !=
        std::string::npos);
  CHECK(transitions.find("12.01,storyboard,,stopTransition") != std::string::npos);
  const auto& rows = run.rows;
  CHECK(row_at(rows, "Ego", 2.0).speed == Approx(20.0));
  CHECK(row_at(rows, "Ego", 12.0).speed == Approx(0.0));
  CHECK(row_at(rows, "Lead", 12.0).speed == Approx(10.0));
  // The source's vehicles (lane -3 from s = 20) reach the sink at s = 60 and go there.
  size_t generated = 0, off_lane = 0;
  double furthest = 0.0;
  for (const TrajectoryRow& row : rows) {
    if (row.entity == "Ego" || row.entity == "Lead") continue;
    ++generated;
    off_lane += row.lane == -3 ? 0 : 1;
    furthest = std::max(furthest, row.s);
  }
  CHECK(generated > 300);
  CHECK(off_lane == 0);
  CHECK(furthest > 50.0);
  CHECK(furthest < 70.0);
}

TEST_CASE("corsa validate --strict refuses a 0.9 draft at its FileHeader", "[e2e][osc09]") {
  const ProcessResult result = run_corsa({"validate", kDraftCutIn, "--strict"});
  CHECK(result.exit_code == 2);
  CHECK(
      result.err.find(kDraftCutIn + ":6: error: OpenSCENARIO 0.9 draft (an error under --strict") !=
      std::string::npos);
}

}  // namespace
}  // namespace corsa::test
