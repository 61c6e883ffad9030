// `corsa sweep DIST.xosc | SCENARIO.xosc --param ...`: the variants of a ParameterValueDistribution
// or a quick grid, on every core or as one shard of a cluster job; `corsa sweep merge` joins the
// shards. The work is in corsa_sweep (sweep/); this file parses, wires and prints.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "args.h"
#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/sweep/merge.h"
#include "corsa/sweep/parallel.h"
#include "corsa/sweep/sweep.h"
#include "stop_signals.h"
#include "sweep_options.h"

namespace corsa::cli {
namespace {

ArgParser sweep_parser() {
  ArgParser parser(
      "sweep DIST.xosc | SCENARIO.xosc --param NAME=VALUES... [options]\n"
      "       corsa sweep merge OUT SHARD_DIR... [--force]",
      "Runs the parameter variants of a ParameterValueDistribution file, or a grid over\n"
      "a scenario's parameters, in parallel or as one shard of a cluster job.");
  parser.positional("FILE.xosc", "ParameterValueDistribution or scenario file");
  parser.repeated("--param", "NAME=VALUES",
                  "grid axis: LOW:HIGH:STEP, a list A,B,C or one value (varies fastest last)");
  parser.option("-o", "DIR", "output folder (default: sweep, or sweep-shard-K for a shard)");
  parser.option("-j", "N", "threads (default: every core)");
  parser.option("--shard", "K/N|auto",
                "run shard K of N (0-based), or read it from Slurm/Kubernetes");
  parser.option("--shard-count", "N", "shard count for --shard auto in a Kubernetes Indexed Job");
  parser.flag("--resume", "keep the variants already done in the output folder, run the rest");
  parser.flag("--force", "replace an earlier sweep in the output folder");
  parser.option("--seed", "N",
                "run seed of every variant, and of a Stochastic distribution "
                "without randomSeed (default 0)");
  parser.option("--dt", "SECONDS", "fixed step (default 0.01)");
  parser.option("--duration", "SECONDS", "stop each run at this simulated time at the latest");
  parser.option("--semantics", "standard|esmini",
                "where the standard's text and esmini differ, read as the standard (default) or "
                "as esmini");
  parser.option("--record-every", "N", "trajectory row every N-th step (default 1)");
  parser.flag("--no-trajectories", "write no trajectory.csv per variant");
  parser.option("--ego", "NAME",
                "entity the metrics are measured for (default: Ego, hero, or "
                "the first entity)");
  parser.flag("--quiet", "no progress bar and no summary line");
  parser.flag("--strict", "refuse lenient readings ('(read as ...)' warnings) in every variant");
  parser.epilog(
      "Writes DIR/sweep.json, DIR/variants/<index>/ (trajectory.csv, summary.json, result.csv)\n"
      "and DIR/summary.csv (index, parameters, status, end reason, sim time, collisions, minimum\n"
      "TTC, minimum distance, maximum deceleration, error, wall time). A failing variant is\n"
      "recorded and the sweep goes on. Exit 0 when every variant ran, 1 when some failed, 2 on\n"
      "bad input. Ctrl-C (or SIGTERM) lets the variants in progress finish and leaves the folder\n"
      "for --resume (exit 130, 143 for SIGTERM). One corsa writes into a folder at a time.\n"
      "examples:\n"
      "  corsa sweep cut_in_grid.xosc -o out\n"
      "  corsa sweep cut_in.xosc --param Ego_Speed=20:40:5 --param Cut_Lane=-1,-2 -o out\n"
      "  corsa sweep dist.xosc --shard auto -o out/shard-$SLURM_ARRAY_TASK_ID   (then: corsa sweep "
      "merge out/all out/shard-*)");
  return parser;
}

std::vector<sweep::GridAxis> grid_axes(const ParsedArgs& parsed) {
  std::vector<sweep::GridAxis> grid;
  // The axes together hold at most 10 million values (each value is a string in memory): four
  // ranges of 9 million took 20 s and 1.1 GB before the variant count was refused. Each axis gets
  // what the axes before it left; the variant count (their product) is checked per process later.
  size_t room = 10'000'000;
  for (const auto& text : parsed.values("--param")) {
    grid.push_back(sweep::parse_grid_axis(text, room));
    room -= grid.back().values.size();
  }
  return grid;
}

void print_report(const sweep::VariantPlan& plan, const sweep::SweepOptions& options,
                  const sweep::SweepReport& report) {
  const double rate = report.wall_seconds > 0.0 ? report.ran / report.wall_seconds : 0.0;
  std::cout << "swept " << report.variants << " variant" << (report.variants == 1 ? "" : "s");
  if (!options.shard.whole()) {
    std::cout << " (shard " << options.shard.text() << " of " << plan.size() << ")";
  }
  std::cout << " of " << plan.scenario().string() << " into " << options.output.string() << ": "
            << report.ran << " ran";
  if (report.resumed > 0) std::cout << ", " << report.resumed << " resumed";
  if (report.skipped > 0) {
    std::cout << ", " << report.skipped << " skipped (values outside the scenario's constraints)";
  }
  std::cout << ", " << report.failed << " failed; " << format_fixed(report.wall_seconds, 2)
            << " s, " << format_fixed(rate, 1) << " variants/s\n";
}

int run_merge(std::span<const std::string> args) {
  ArgParser parser("sweep merge OUT SHARD_DIR... [--force]",
                   "Joins the output folders of a sweep's shards into OUT, as the unsharded sweep\n"
                   "would have written it.");
  parser.positional("OUT SHARD_DIR...", "merged output folder, then the shard folders", 2, -1);
  parser.flag("--force", "replace OUT if it exists");
  parser.flag("--quiet", "no summary line");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const auto& positionals = parsed.positionals();
  const std::vector<std::filesystem::path> shards(positionals.begin() + 1, positionals.end());
  const auto report = sweep::merge_sweeps(positionals.front(), shards, parsed.flag("--force"));
  if (!parsed.flag("--quiet")) {
    std::cout << "merged " << report.shards << " shard" << (report.shards == 1 ? "" : "s")
              << " into " << positionals.front() << ": " << report.variants << " variants, "
              << report.failed << " failed\n";
  }
  return report.failed > 0 ? kExitFailed : kExitOk;
}

int run_sweep_command(std::span<const std::string> args) {
  const ArgParser parser = sweep_parser();
  const ParsedArgs parsed = parser.parse(split_jobs_option(args));
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  sweep::SweepOptions options = sweep_options(parsed);
  const bool quiet = parsed.flag("--quiet");
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  const sweep::VariantPlan plan =
      sweep::VariantPlan::from_file(parsed.positionals().front(), grid_axes(parsed),
                                    options.simulation.seed, diagnostics, parsed.flag("--strict"));
  ProgressBar progress("sweep", static_cast<double>(options.shard.share(plan.size())), !quiet);
  const StopSignals signals;
  options.stop = [] { return StopSignals::reason(); };
  const sweep::SweepReport report = sweep::run_sweep(
      plan, options, diagnostics, [&](size_t done, size_t) { progress.update(double(done)); });
  progress.finish();
  if (report.interruption) {
    std::cerr << "corsa sweep: " << *report.interruption << "; " << options.output.string()
              << " holds " << report.ran + report.resumed << " of " << report.variants
              << " variants, complete (finish with --resume)\n";
    return StopSignals::exit_code();
  }
  if (!quiet) print_report(plan, options, report);
  for (const auto& [index, error] : report.first_failures) {
    std::cerr << "variant " << index << " failed: " << error << '\n';
  }
  if (report.failed > report.first_failures.size()) {
    std::cerr << "... and " << report.failed - report.first_failures.size()
              << " more failed variants (see summary.csv)\n";
  }
  return report.failed > 0 ? kExitFailed : kExitOk;
}

}  // namespace

int command_sweep(std::span<const std::string> args) {
  // An output folder that cannot be written is the user's to fix: guarded() says so (exit 2).
  if (!args.empty() && args.front() == "merge") return run_merge(args.subspan(1));
  return run_sweep_command(args);
}

}  // namespace corsa::cli
