// `corsa run SCENARIO.xosc`: runs one scenario headless with a fixed step (engine::run_scenario)
// and prints a one-line summary; a progress bar on a terminal.

#include <iostream>
#include <optional>
#include <string>

#include "args.h"
#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/engine/run.h"
#include "corsa/sweep/distribution_run.h"
#include "plugin_api.h"
#include "run_options.h"

namespace corsa::cli {

int command_run(std::span<const std::string> args) {
  // Sensors need Embree and OpenCV, which live in the plugin: a run with a rig is the plugin's.
  for (const std::string& arg : args) {
    if (arg == "--rig" || arg.starts_with("--rig=")) {
      return run_plugin_command("run", args);
    }
  }
  ArgParser parser(
      "run SCENARIO.xosc [options]",
      "Runs one OpenSCENARIO scenario headless with a fixed step and writes its outputs.");
  declare_run_options(parser);
  declare_dataset_options(parser);
  parser.epilog(
      "The run ends at the storyboard's stop trigger, when every story is complete (without a\n"
      "stop trigger), or at --duration. Exit 0 when it ran, 2 on bad input.\n"
      "With --rig RIG.xml -o DIR the run also captures a dataset (docs/datasets.md).\n"
      "example: corsa run scenarios/cut_in.xosc --record out.csv --summary out.json\n"
      "example: corsa run scenarios/demo/cut_in_city.xosc --rig scenarios/demo/rig.xml -o out");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  if (const std::optional<std::string> dataset = dataset_option_given(parsed)) {
    throw UsageError(*dataset + " is a dataset option: it needs --rig RIG.xml");
  }
  engine::RunOptions options = read_run_options(parsed);
  options.simulation.geo_projection = proj_plugin_geo_projection();
  const bool quiet = parsed.flag("--quiet");
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  sweep::read_distribution_as_scenario(options, diagnostics);
  ProgressBar progress("run", options.simulation.duration, !quiet);
  // The bar's end is the scenario's own (its SimulationTime stop trigger), once it is loaded.
  options.prepare = [&progress](engine::Simulation& simulation) {
    progress.set_total(
        engine::expected_end_time(simulation.scenario(), simulation.options().duration));
  };
  const engine::RunReport report =
      engine::run_scenario(options, diagnostics, [&](const engine::Simulation& simulation) {
        // The bar redraws itself at most ~10 times a second; feeding it every 64 steps is plenty.
        if (progress.visible() && simulation.tick() % 64 == 0) {
          progress.update(simulation.time());
        }
      });
  progress.complete();
  if (!quiet) {
    const double factor = report.wall_seconds > 0.0 ? report.sim_time / report.wall_seconds : 0.0;
    std::cout << options.scenario.string() << ": ended by " << engine::to_string(report.end_reason)
              << " at " << format_fixed(report.sim_time, 2) << " s simulated"
              << (report.start_time < 0.0 ? " from " + format_fixed(report.start_time, 2) + " s"
                                          : "")
              << ", " << report.steps << " steps, " << format_fixed(report.wall_seconds, 3)
              << " s wall (" << format_fixed(factor, 0) << "x real time)";
    if (report.collisions > 0) {
      std::cout << ", " << report.collisions << " collision" << (report.collisions == 1 ? "" : "s");
    }
    std::cout << '\n' << engine::collision_lines(report);
  }
  return kExitOk;
}

}  // namespace corsa::cli
