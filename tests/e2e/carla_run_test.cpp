// `corsa run` on the forms of CARLA scenario_runner's OpenSCENARIO 1.0 examples
// (srunner/examples: ParameterActionTest, InitDeleteEntityAction, LaneOffsetActionExample,
// ChangingWeather), written small in tests/xosc/fixtures/carla (CARLA's own files name towns
// the store lacks: Town01).

#include "csv_compare.h"
#include "recorded_run.h"
#include "run_corsa.h"

namespace corsa::test {
namespace {

const std::string kCarlaForms = "tests/xosc/fixtures/carla/init_parameters_delete_offset.xosc";

TEST_CASE(
    "corsa run performs CARLA's Init ParameterActions, Init DeleteEntityAction, a relative "
    "LaneOffsetAction and an empty Action",
    "[e2e][run][carla]") {
  const RecordedRun run = run_recorded(kCarlaForms);
  const ProcessResult& result = run.result;
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK(result.err.find(kCarlaForms + ":181: warning: <Action> 'DummyAction' without an action "
                                      "(read as an action that does nothing") != std::string::npos);
  const std::string& transitions = run.log;
  const std::string group = "MyStory::Behavior::ManeuverSequence::";
  // The Init ParameterActions made finalSpeed 36 x 0.277778 + 8: the condition sees it at once.
  CHECK(transitions.find("0.01,event," + group + "ParameterManeuver::SpeedKnown,startTransition") !=
        std::string::npos);
  CHECK(transitions.find("4.01,event," + group +
                         "WeatherChange::WeatherChangeEvent,endTransition") != std::string::npos);
  // Empty StopTriggers: the storyboard ends with its story.
  CHECK(transitions.find("4.01,storyboard,,endTransition") != std::string::npos);
  const auto& rows = run.rows;
  CHECK(of(rows, "adversary2").empty());  // deleted in Init
  CHECK(row_at(rows, "adversary", 0.5).speed == Approx(8.0));
  // $finalSpeed in the event is the declared 5: references are resolved at load.
  CHECK(row_at(rows, "adversary", 1.5).speed == Approx(5.0));
  // hero keeps 0.5 m right of the adversary's offset (0) in their lane (centre t = -1.875).
  CHECK(row_at(rows, "hero", 0.0).t == Approx(-1.875));
  CHECK(row_at(rows, "hero", 4.0).t == Approx(-2.375).margin(1e-6));
  CHECK(row_at(rows, "hero", 4.0).lane == -1);
}

}  // namespace
}  // namespace corsa::test
