#pragma once

// `corsa run FILE --quiet` with its trajectory and its transition log recorded into a fresh
// folder, both read back before the folder goes.

#include <string>
#include <vector>

#include "csv_compare.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace corsa::test {

struct RecordedRun {
  ProcessResult result;
  std::string log;                  ///< the transition log (`--log`) as written
  std::vector<TrajectoryRow> rows;  ///< the trajectory (`--record`); empty when the run failed
};

inline RecordedRun run_recorded(const std::string& file) {
  TempDir dir;
  const auto record = dir.path() / "out.csv";
  const auto log = dir.path() / "log.csv";
  RecordedRun run;
  run.result =
      run_corsa({"run", file, "--quiet", "--record", record.string(), "--log", log.string()});
  if (run.result.exit_code == 0) {
    run.log = slurp(log);
    run.rows = parse_trajectory(slurp(record));
  }
  return run;
}

}  // namespace corsa::test
