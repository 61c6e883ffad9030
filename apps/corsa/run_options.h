#pragma once

// The options of `corsa run` that drive the engine (scenario, parameters, step, duration, seed,
// controller, outputs, --quiet), shared by the executable's `run` and the plugin's `run --rig`
// so that both accept and check exactly the same ones.

#include <optional>
#include <string>

#include "args.h"
#include "corsa/engine/run.h"

namespace corsa::cli {

/// Declares SCENARIO.xosc and the engine's options on `parser`.
void declare_run_options(ArgParser& parser);

/// Reads what declare_run_options declared; throws UsageError for bad values.
engine::RunOptions read_run_options(const ParsedArgs& parsed);

/// The `--semantics standard|esmini` option (run and sweep); throws UsageError for other values.
engine::Semantics read_semantics(const ParsedArgs& parsed);

/// Declares the dataset options (--rig, -o, --format, --force, --time-of-day, --weather,
/// --model, --preview) under their own --help heading. The executable declares them too, so
/// that `corsa run --help` lists them and a dataset option without --rig gets a clear message.
void declare_dataset_options(ArgParser& parser);

/// The first dataset option given, if any (for "needs --rig").
std::optional<std::string> dataset_option_given(const ParsedArgs& parsed);

}  // namespace corsa::cli
