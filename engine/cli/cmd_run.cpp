// `corsa run SCENARIO.xosc`: runs one scenario headless with a fixed step (engine::run_scenario)
// and prints a one-line summary; a progress bar on a terminal.

#include <cmath>
#include <iostream>

#include "args.h"
#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/engine/run.h"
#include "plugin_api.h"

namespace corsa::cli {
namespace {

engine::RunOptions run_options(const ParsedArgs& parsed) {
  engine::RunOptions options;
  options.scenario = parsed.positionals().front();
  for (const auto& assignment : parsed.values("--param")) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UsageError("--param expects NAME=VALUE, got '" + assignment + "'");
    }
    options.parameters.emplace_back(assignment.substr(0, eq), assignment.substr(eq + 1));
  }
  if (const auto dt = parsed.number("--dt")) {
    if (!(*dt > 0.0) || *dt > 10.0) {
      throw UsageError("--dt expects a step in seconds, 0 < dt <= 10");
    }
    options.simulation.dt = *dt;
  }
  if (const auto duration = parsed.number("--duration")) {
    if (!(*duration >= 0.0) || !std::isfinite(*duration)) {
      throw UsageError("--duration expects a number of seconds >= 0");
    }
    options.simulation.duration = *duration;
  }
  if (const auto seed = parsed.integer("--seed")) {
    if (*seed < 0) {
      throw UsageError("--seed expects a non-negative integer");
    }
    options.simulation.seed = static_cast<uint64_t>(*seed);
  }
  if (auto controller = parsed.value("--controller")) {
    if (*controller != "default" && *controller != "acc" && *controller != "dynamics") {
      throw UsageError("--controller expects default, acc or dynamics");
    }
    options.simulation.controller = *controller;
  }
  if (const auto every = parsed.integer("--record-every")) {
    if (*every < 1) {
      throw UsageError("--record-every expects a positive integer");
    }
    options.record_every = *every;
  }
  if (auto record = parsed.value("--record")) {
    options.record = *record;
  }
  if (auto summary = parsed.value("--summary")) {
    options.summary = *summary;
  }
  if (auto log = parsed.value("--log")) {
    options.log = *log;
  }
  return options;
}

}  // namespace

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
  parser.positional("SCENARIO.xosc", "the scenario to run");
  parser.repeated("--param", "NAME=VALUE", "override a global scenario parameter");
  parser.option("--dt", "SECONDS", "fixed step (default 0.01)");
  parser.option("--duration", "SECONDS",
                "stop at this simulated time at the latest (default 3600)");
  parser.option("--seed", "N", "run seed for random draws (default 0)");
  parser.option("--controller", "NAME",
                "controller of every vehicle the scenario gives none: default, acc, dynamics");
  parser.option("--record", "FILE.csv", "write the trajectories (time,entity,x,y,z,h,p,r,...)");
  parser.option("--record-every", "N", "record every N-th step (default 1)");
  parser.option("--summary", "FILE.json", "write the run summary");
  parser.option("--log", "FILE.csv", "write every storyboard transition with its time");
  parser.flag("--quiet", "no progress bar and no summary line");
  parser.epilog(
      "The run ends at the storyboard's stop trigger, when every story is complete (without a\n"
      "stop trigger), or at --duration. Exit 0 when it ran, 2 on bad input.\n"
      "With --rig RIG.xml -o DIR the run also captures a dataset (docs/datasets.md; see\n"
      "'corsa run --rig x --help').\n"
      "example: corsa run scenarios/cut_in.xosc --record out.csv --summary out.json");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const engine::RunOptions options = run_options(parsed);
  const bool quiet = parsed.flag("--quiet");
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  ProgressBar progress("run", options.simulation.duration, !quiet);
  const engine::RunReport report =
      engine::run_scenario(options, diagnostics, [&](const engine::Simulation& simulation) {
        // The bar redraws itself at most ~10 times a second; feeding it every 64 steps is plenty.
        if (progress.visible() && simulation.tick() % 64 == 0) {
          progress.update(simulation.time());
        }
      });
  progress.finish();
  if (!quiet) {
    const double factor = report.wall_seconds > 0.0 ? report.sim_time / report.wall_seconds : 0.0;
    std::cout << options.scenario.string() << ": ended by " << engine::to_string(report.end_reason)
              << " at " << format_fixed(report.sim_time, 2) << " s simulated, " << report.steps
              << " steps, " << format_fixed(report.wall_seconds, 3) << " s wall ("
              << format_fixed(factor, 0) << "x real time)";
    if (report.collisions > 0) {
      std::cout << ", " << report.collisions << " collision" << (report.collisions == 1 ? "" : "s");
    }
    std::cout << '\n';
  }
  return kExitOk;
}

}  // namespace corsa::cli
