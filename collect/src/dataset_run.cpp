// A whole data-collection run (dataset_run.h).
//
// engine::run_scenario with a `prepare` hook that sets up the DataRun once the simulation exists.
// A stop request is checked between steps (RunOptions::stop): the capture in progress always
// completes, the run ends as interrupted, and both the engine's outputs (--record, --summary,
// --log) and the dataset say where it stopped.

#include "corsa/collect/dataset_run.h"

#include <optional>
#include <string>

#include "corsa/collect/data_run.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/sensor_system.h"

namespace corsa::collect {

DatasetRunReport run_dataset(const DatasetRunOptions& options, Diagnostics& diagnostics,
                             const DatasetRunHooks& hooks) {
  DataRun data(options, diagnostics, sensors::load_rig(options.rig));
  engine::RunOptions run = options.run;
  run.prepare = [&options, &data](engine::Simulation& simulation) {
    if (options.run.prepare) {
      options.run.prepare(simulation);
    }
    data.prepare(simulation);
  };
  DatasetRunReport report;
  std::optional<std::string> stop_reason;
  if (hooks.stop) {
    run.stop = [&hooks, &stop_reason] {
      stop_reason = hooks.stop();
      return stop_reason.has_value();
    };
  }
  report.run = engine::run_scenario(run, diagnostics, [&](const engine::Simulation& simulation) {
    data.observe(simulation);  // where the run is, for run.json
    if (hooks.on_step) {
      hooks.on_step(simulation);
    }
  });
  if (report.run.end_reason == engine::EndReason::kInterrupted) {
    report.interrupted = true;
    report.interruption = stop_reason.value_or("interrupted");
  }
  if (hooks.on_simulated) {
    hooks.on_simulated();
  }
  if (report.interrupted) {
    data.finish("interrupted", report.interruption);
  } else {
    data.finish("complete", std::string(engine::to_string(report.run.end_reason)));
  }
  report.dataset_started = data.started();
  report.captures = data.captures();
  report.files = data.files();
  if (!report.interrupted && options.preview) {
    const std::optional<sensors::StreamedVideo> streamed = data.take_preview_video();
    report.preview = sensors::write_preview(options.output, data.system().rig(), diagnostics,
                                            hooks.on_preview, streamed ? &*streamed : nullptr);
  }
  return report;
}

}  // namespace corsa::collect
