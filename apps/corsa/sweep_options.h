#pragma once

// The options of `corsa sweep` turned into sweep::SweepOptions (usage errors thrown here).

#include <span>
#include <string>
#include <vector>

#include "args.h"
#include "corsa/sweep/sweep.h"

namespace corsa::cli {

/// The arguments with `-jN` written as `-j N` (make's spelling, which ArgParser does not split).
std::vector<std::string> split_jobs_option(std::span<const std::string> args);

/// -o, -j, --shard/--shard-count (auto reads the process environment), --resume, --force, --seed,
/// --dt, --duration, --record-every, --no-trajectories, --ego.
sweep::SweepOptions sweep_options(const ParsedArgs& parsed);

}  // namespace corsa::cli
