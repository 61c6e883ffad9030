#pragma once

// `corsa run SCENARIO --rig RIG -o DIR` in the plugin (the corsa executable delegates every
// `run` with --rig here): its options, read into collect::DatasetRunOptions. The run itself is
// collect::run_dataset.

#include "args.h"
#include "corsa/collect/dataset_run.h"

namespace corsa::cli {

struct RigRunOptions {
  collect::DatasetRunOptions dataset;
  bool quiet = false;  ///< no progress bar, no summary lines
};

/// Declares the options of the plugin's `run` (the engine's options plus the sensor ones).
void declare_rig_run_options(ArgParser& parser);
/// Reads them; throws UsageError for bad values.
RigRunOptions read_rig_run_options(const ParsedArgs& parsed);

}  // namespace corsa::cli
