// corsa_conformance: loads and runs every OpenSCENARIO scenario under the given files or folders
// and says which run to their stop trigger. A report, not a test (the conformance tests assert
// on ../shared/conformance); use it on a scenario library before adopting Corsa:
//
//   corsa_conformance ../shared/conformance                 every ALKS and ASAM scenario
//   corsa_conformance --sweep 24 ../shared/conformance      ... and a 24-variant sample of
//                                                            every variation file
//   corsa_conformance --duration 120 ~/esmini/resources/xosc
//
// One line per file: the outcome (stop trigger, stories complete, duration, load error, run
// error), simulated and wall time, how many lenient readings ("read as") and unsupported
// features warned, and the first error. Then the totals. Exit 0 (it reports); 2 for a usage
// error or a folder that cannot be listed.

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/sweep/sweep.h"
#include "corsa/xosc/scenario.h"

namespace fs = std::filesystem;

namespace {

struct Options {
  std::vector<fs::path> inputs;
  double duration = 600.0;
  size_t sweep_variants = 0;  ///< 0: do not sweep variation files
  bool strict = false;
  bool help = false;
  std::string usage_error;  ///< set for an option it does not know or a value it cannot read
};

constexpr const char* kUsage =
    "usage: corsa_conformance [--duration S] [--sweep N] [--strict] PATH...\n";

struct Totals {
  size_t scenarios = 0;
  size_t stop_trigger = 0;
  size_t stories_complete = 0;
  size_t duration = 0;
  size_t load_errors = 0;
  size_t run_errors = 0;
  size_t distributions = 0;
  size_t distributions_clean = 0;
};

enum class Kind { kScenario, kDistribution, kOther };

/// Whether `text` has the element `name` (not merely one whose name starts with it, as
/// <StoryboardElementStateCondition> in a maneuver catalog starts with <Storyboard).
bool has_element(const std::string& text, const std::string& name) {
  const std::string open = "<" + name;
  for (size_t at = text.find(open); at != std::string::npos; at = text.find(open, at + 1)) {
    const size_t next = at + open.size();
    if (next < text.size() && (text[next] == '>' || text[next] == '/' ||
                               std::isspace(static_cast<unsigned char>(text[next])) != 0)) {
      return true;
    }
  }
  return false;
}

Kind kind_of(const fs::path& file) {
  const std::string text = corsa::read_file(file);
  if (has_element(text, "ParameterValueDistribution")) return Kind::kDistribution;
  if (has_element(text, "Storyboard")) return Kind::kScenario;
  return Kind::kOther;
}

std::vector<fs::path> collect(const std::vector<fs::path>& inputs) {
  std::vector<fs::path> files;
  for (const auto& input : inputs) {
    if (fs::is_directory(input)) {
      for (const auto& entry : fs::recursive_directory_iterator(input)) {
        if (entry.is_regular_file() && entry.path().extension() == ".xosc") {
          files.push_back(entry.path());
        }
      }
    } else {
      files.push_back(input);
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

size_t count_with(const std::vector<corsa::Diagnostic>& all, const std::string& text) {
  return static_cast<size_t>(std::count_if(all.begin(), all.end(), [&](const auto& d) {
    return d.severity == corsa::Severity::kWarning && d.message.find(text) != std::string::npos;
  }));
}

void run_scenario(const fs::path& file, const Options& options, Totals& totals) {
  ++totals.scenarios;
  corsa::Diagnostics diagnostics;
  corsa::xosc::LoadOptions load;
  load.strict = options.strict;
  corsa::engine::SimulationOptions simulation;
  simulation.duration = options.duration;
  simulation.strict = options.strict;
  const auto start = std::chrono::steady_clock::now();
  std::string outcome = "load error";
  std::string error;
  double sim_time = 0.0;
  try {
    const corsa::xosc::Scenario scenario = corsa::xosc::load_scenario(file, load, diagnostics);
    auto map = corsa::engine::load_road_network(scenario, diagnostics);
    outcome = "run error";
    corsa::engine::Simulation run(scenario, std::move(map), simulation, diagnostics);
    run.run();
    outcome = std::string(corsa::engine::to_string(run.end_reason()));
    sim_time = run.time();
    switch (run.end_reason()) {
      case corsa::engine::EndReason::kStopTrigger:
        ++totals.stop_trigger;
        break;
      case corsa::engine::EndReason::kStoriesComplete:
        ++totals.stories_complete;
        break;
      default:
        ++totals.duration;
    }
  } catch (const corsa::InputError& caught) {
    error = caught.brief();
    ++(outcome == "load error" ? totals.load_errors : totals.run_errors);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto all = diagnostics.all();
  std::printf("%-70s %-16s %8.2f s %7.3f s  lenient %2zu  unsupported %2zu  %s\n",
              file.string().c_str(), outcome.c_str(), sim_time, wall, count_with(all, "(read as "),
              count_with(all, "not supported") + count_with(all, "not performed") +
                  count_with(all, "not evaluated"),
              corsa::clip(error, 160).c_str());
}

void sweep_distribution(const fs::path& file, const Options& options, Totals& totals) {
  ++totals.distributions;
  corsa::Diagnostics diagnostics;
  std::string line;
  try {
    const auto distribution = corsa::xosc::load_distribution(file, diagnostics);
    const auto plan = corsa::sweep::VariantPlan::from_distribution(file, distribution, {}, 0);
    corsa::sweep::SweepOptions sweep;
    const fs::path output =
        fs::temp_directory_path() / ("corsa-conformance-" + std::to_string(::getpid()));
    sweep.output = output;
    sweep.force = true;
    sweep.trajectories = false;
    sweep.simulation.duration = options.duration;
    sweep.simulation.strict = options.strict;
    sweep.shard.count =
        std::max<size_t>(1, (plan.size() + options.sweep_variants - 1) / options.sweep_variants);
    const auto report = corsa::sweep::run_sweep(plan, sweep, diagnostics);
    fs::remove_all(output);
    totals.distributions_clean += report.failed == 0 ? 1 : 0;
    line = std::to_string(report.variants) + " of " + std::to_string(plan.size()) +
           " variants: " + std::to_string(report.variants - report.failed - report.skipped) +
           " ran, " + std::to_string(report.skipped) + " skipped, " +
           std::to_string(report.failed) + " failed";
    if (!report.first_failures.empty()) line += "; first: " + report.first_failures[0].second;
  } catch (const corsa::InputError& caught) {
    line = "error: " + caught.brief();
  }
  std::printf("%-70s sweep  %s\n", file.string().c_str(), corsa::clip(line, 240).c_str());
}

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--duration" || arg == "--sweep") {
      const std::string value = i + 1 < argc ? argv[++i] : "";
      bool read = false;
      if (arg == "--duration") {
        const double seconds = corsa::parse_double(value).value_or(-1.0);
        read = seconds > 0.0;
        if (read) options.duration = seconds;
      } else {
        const int64_t count = corsa::parse_int(value).value_or(-1);
        read = count >= 0;
        if (read) options.sweep_variants = static_cast<size_t>(count);
      }
      if (!read) {
        options.usage_error = arg + " needs a number (seconds above 0, a variant count), not '" +
                              corsa::clip(value) + "'";
      }
    } else if (arg == "--strict") {
      options.strict = true;
    } else if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if (arg.rfind("--", 0) == 0) {
      options.usage_error = "unknown option " + corsa::clip(arg);
    } else {
      options.inputs.emplace_back(arg);
    }
  }
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  if (options.help) {
    std::cout << kUsage;
    return 0;
  }
  if (!options.usage_error.empty() || options.inputs.empty()) {
    if (!options.usage_error.empty())
      std::cerr << "corsa_conformance: " << options.usage_error << '\n';
    std::cerr << kUsage;
    return 2;
  }
  Totals totals;
  std::vector<fs::path> files;
  try {
    files = collect(options.inputs);
  } catch (const fs::filesystem_error& error) {
    std::cerr << "corsa_conformance: " << error.what() << '\n';
    return 2;
  }
  for (const fs::path& file : files) {
    Kind kind = Kind::kOther;
    try {
      kind = kind_of(file);
    } catch (const corsa::InputError& error) {
      std::cerr << error.what() << '\n';  // an unreadable path: said, and the others still run
    }
    if (kind == Kind::kScenario) run_scenario(file, options, totals);
    if (kind == Kind::kDistribution && options.sweep_variants > 0) {
      sweep_distribution(file, options, totals);
    }
  }
  std::printf(
      "\n%zu scenarios: %zu ran to their stop trigger, %zu ended with their last story (no stop "
      "trigger), %zu ran until the duration, %zu failed to load, %zu failed while running\n",
      totals.scenarios, totals.stop_trigger, totals.stories_complete, totals.duration,
      totals.load_errors, totals.run_errors);
  if (options.sweep_variants > 0) {
    std::printf("%zu variation files: %zu swept without a failed variant\n", totals.distributions,
                totals.distributions_clean);
  }
  return 0;
}
