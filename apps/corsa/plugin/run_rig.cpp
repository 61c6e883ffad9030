// `corsa run SCENARIO --rig RIG -o DIR` (plugin side; see run_rig.h and docs/datasets.md): parses
// the options, runs collect::run_dataset and prints. SIGINT and SIGTERM only set a flag
// (StopSignals); the run asks for it between steps (DatasetRunHooks::stop) and ends after the
// capture in progress, so the dataset says where it stopped.

#include "run_rig.h"

#include <iostream>
#include <optional>

#include "commands.h"
#include "corsa/collect/dataset_run.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "plugin_commands.h"
#include "stop_signals.h"

namespace corsa::cli {
namespace {

int run_rig_body(std::span<const std::string> args) {
  ArgParser parser("run SCENARIO.xosc --rig RIG.xml -o DIR [options]",
                   "Runs one OpenSCENARIO scenario with a sensor rig and writes a dataset: "
                   "frames.csv, one folder per sensor, calibration, poses, labels, run.json.");
  declare_rig_run_options(parser);
  parser.epilog(
      "Capture windows come from CustomCommandAction type=\"corsa:capture\" (docs/datasets.md);\n"
      "without one the whole run is captured. Ctrl-C stops after the current capture and leaves\n"
      "a consistent dataset (run.json status \"interrupted\"); exit 130 then.\n"
      "example: corsa run scenarios/demo/cut_in_city.xosc --rig scenarios/demo/rig.xml -o out");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const RigRunOptions options = read_rig_run_options(parsed);
  const collect::DatasetRunOptions& dataset = options.dataset;
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  ProgressBar progress("run", dataset.run.simulation.duration, !options.quiet);
  const StopSignals signals;
  collect::DatasetRunHooks hooks;
  hooks.on_step = [&progress](const engine::Simulation& sim) {
    if (progress.visible() && sim.tick() % 16 == 0) {
      progress.update(sim.time());
    }
  };
  hooks.stop = [] { return StopSignals::reason(); };
  hooks.on_simulated = [&progress] { progress.finish(); };
  const collect::DatasetRunReport report = collect::run_dataset(dataset, diagnostics, hooks);
  if (report.interrupted) {
    if (report.dataset_started) {
      std::cerr << "corsa run: " << report.interruption << "; " << dataset.output.string()
                << " holds " << report.captures
                << " complete captures (run.json status \"interrupted\")\n";
    } else {
      std::cerr << "corsa run: " << report.interruption << " before the first capture\n";
    }
    return StopSignals::exit_code();
  }
  if (report.preview && !options.quiet) {
    std::cout << report.preview->summary << '\n';
  }
  if (!options.quiet) {
    std::cout << dataset.run.scenario.string() << ": ended by "
              << engine::to_string(report.run.end_reason) << " at "
              << format_fixed(report.run.sim_time, 2) << " s simulated, " << report.captures
              << " captures, " << report.files << " files in " << dataset.output.string() << ", "
              << format_fixed(report.run.wall_seconds, 1) << " s wall\n";
  }
  return kExitOk;
}

}  // namespace

int plugin_run(std::span<const std::string> args) { return guarded("run", run_rig_body, args); }

}  // namespace corsa::cli
