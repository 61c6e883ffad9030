// `corsa run SCENARIO --rig RIG -o DIR` (plugin side; see run_rig.h and docs/datasets.md): parses
// the options, runs collect::run_dataset and prints. SIGINT and SIGTERM only set a flag
// (StopSignals); the run asks for it between steps (DatasetRunHooks::stop) and ends after the
// capture in progress, so the dataset says where it stopped.

#include "run_rig.h"

#include <chrono>
#include <iostream>
#include <optional>

#include "commands.h"
#include "corsa/collect/dataset_run.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/engine/run.h"
#include "corsa/sweep/distribution_run.h"
#include "plugin_commands.h"
#include "run_options.h"
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
  const auto start = std::chrono::steady_clock::now();  // the summary counts all of it
  const RigRunOptions options = read_rig_run_options(parsed);
  collect::DatasetRunOptions dataset = options.dataset;
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  sweep::read_distribution_as_scenario(dataset.run, diagnostics);
  ProgressBar progress("run", dataset.run.simulation.duration, !options.quiet);
  // The bar's end is the scenario's own (its SimulationTime stop trigger), once it is loaded.
  dataset.run.prepare = [&progress](engine::Simulation& simulation) {
    progress.set_total(
        engine::expected_end_time(simulation.scenario(), simulation.options().duration));
  };
  const StopSignals signals;
  collect::DatasetRunHooks hooks;
  hooks.on_step = [&progress](const engine::Simulation& sim) {
    if (progress.visible() && sim.tick() % 16 == 0) {
      progress.update(sim.time());
    }
  };
  hooks.stop = [] { return StopSignals::reason(); };
  hooks.on_simulated = [&progress] {
    if (!StopSignals::reason()) {
      progress.complete();  // ended by itself: all of it
    } else {
      progress.finish();
    }
  };
  bool encoding = false;
  hooks.on_preview = [&progress, &encoding](int done, int total) {
    if (!encoding) {
      progress.restart("preview video", total);
      encoding = true;
    }
    progress.update(done);
  };
  const collect::DatasetRunReport report = collect::run_dataset(dataset, diagnostics, hooks);
  progress.finish();
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
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << dataset.run.scenario.string() << ": ended by "
              << engine::to_string(report.run.end_reason) << " at "
              << format_fixed(report.run.sim_time, 2) << " s simulated, " << report.captures
              << " captures, " << report.files << " files in " << dataset.output.string();
    if (report.run.collisions > 0) {
      std::cout << ", " << report.run.collisions << " collision"
                << (report.run.collisions == 1 ? "" : "s");
    }
    std::cout << ", " << format_fixed(wall, 1) << " s wall in all\n"
              << engine::collision_lines(report.run);
  }
  return kExitOk;
}

}  // namespace

int plugin_run(std::span<const std::string> args) { return guarded("run", run_rig_body, args); }

}  // namespace corsa::cli
