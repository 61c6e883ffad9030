#include "sweep_options.h"

#include <cmath>
#include <cstdlib>

#include "output_paths.h"
#include "plugin_api.h"
#include "run_options.h"

namespace corsa::cli {
namespace {

sweep::Shard shard_option(const ParsedArgs& parsed) {
  const auto text = parsed.value("--shard");
  std::optional<size_t> count;
  if (const auto n = parsed.integer("--shard-count")) {
    if (*n < 1) throw UsageError("--shard-count expects a positive integer");
    count = static_cast<size_t>(*n);
  }
  if (!text) {
    if (count) throw UsageError("--shard-count goes with --shard auto");
    return {};
  }
  if (*text != "auto") {
    if (count) throw UsageError("--shard-count goes with --shard auto, not --shard K/N");
    return sweep::parse_shard(*text);
  }
  return sweep::shard_from_environment(
      [](const std::string& name) -> std::optional<std::string> {
        const char* value = std::getenv(name.c_str());
        return value == nullptr ? std::nullopt : std::optional<std::string>(value);
      },
      count);
}

void simulation_options(const ParsedArgs& parsed, engine::SimulationOptions& simulation) {
  simulation.geo_projection = proj_plugin_geo_projection();
  if (const auto dt = parsed.number("--dt")) {
    // At least 0.1 ms: a step of 1e-300 s is endless steps, a hang rather than a run.
    if (!(*dt >= 1e-4) || *dt > 10.0)
      throw UsageError("--dt expects a step in seconds, 0.0001 <= dt <= 10");
    simulation.dt = *dt;
  }
  if (const auto duration = parsed.number("--duration")) {
    if (!(*duration >= 0.0) || !std::isfinite(*duration)) {
      throw UsageError("--duration expects a number of seconds >= 0");
    }
    simulation.duration = *duration;
  }
  if (const auto seed = parsed.integer("--seed")) {
    if (*seed < 0) throw UsageError("--seed expects a non-negative integer");
    simulation.seed = static_cast<uint64_t>(*seed);
  }
  simulation.strict = parsed.flag("--strict");
  simulation.semantics = read_semantics(parsed);
}

}  // namespace

std::vector<std::string> split_jobs_option(std::span<const std::string> args) {
  std::vector<std::string> out;
  for (const auto& arg : args) {
    if (arg.size() > 2 && arg.rfind("-j", 0) == 0 && arg[2] != '=') {
      out.emplace_back("-j");
      out.push_back(arg.substr(2));
    } else {
      out.push_back(arg);
    }
  }
  return out;
}

sweep::SweepOptions sweep_options(const ParsedArgs& parsed) {
  sweep::SweepOptions options;
  options.shard = shard_option(parsed);
  options.output = output_folder(
      parsed, "-o",
      options.shard.whole() ? "sweep" : "sweep-shard-" + std::to_string(options.shard.index));
  if (const auto jobs = parsed.integer("-j")) {
    if (*jobs < 1) throw UsageError("-j expects a positive number of threads");
    options.jobs = static_cast<size_t>(*jobs);
  }
  options.resume = parsed.flag("--resume");
  options.force = parsed.flag("--force");
  if (options.resume && options.force) throw UsageError("--resume and --force exclude each other");
  simulation_options(parsed, options.simulation);
  if (const auto every = parsed.integer("--record-every")) {
    if (*every < 1) throw UsageError("--record-every expects a positive integer");
    options.record_every = *every;
  }
  options.trajectories = !parsed.flag("--no-trajectories");
  options.ego = parsed.value_or("--ego", "");
  return options;
}

}  // namespace corsa::cli
