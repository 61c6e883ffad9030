#pragma once

// The options of `corsa run` that drive the engine (scenario, parameters, step, duration, seed,
// controller, outputs, --quiet), shared by the executable's `run` and the plugin's `run --rig`
// so that both accept and check exactly the same ones.

#include "args.h"
#include "corsa/engine/run.h"

namespace corsa::cli {

/// Declares SCENARIO.xosc and the engine's options on `parser`.
void declare_run_options(ArgParser& parser);

/// Reads what declare_run_options declared; throws UsageError for bad values.
engine::RunOptions read_run_options(const ParsedArgs& parsed);

}  // namespace corsa::cli
