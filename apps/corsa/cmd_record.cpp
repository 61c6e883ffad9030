// `corsa record ACTION ...`: binary trajectories (`corsa run --record FILE.corsatraj`):
// `export` writes the trajectory CSV the run would have written, `info` says what a file holds.

#include <filesystem>
#include <iostream>

#include "actions.h"
#include "args.h"
#include "commands.h"
#include "corsa/core/strings.h"
#include "corsa/engine/trajectory_file.h"
#include "output_paths.h"

namespace corsa::cli {
namespace {

int record_export(std::span<const std::string> args) {
  ArgParser parser("record export RUN.corsatraj -o OUT.csv",
                   "Writes the trajectory CSV of a binary trajectory: byte for byte the file "
                   "`corsa run --record OUT.csv` writes.");
  parser.positional("RUN.corsatraj", "the binary trajectory (corsa run --record FILE.corsatraj)");
  parser.option("-o", "OUT.csv", "the CSV to write");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const std::filesystem::path out =
      required_output_file(parsed, "-o", "OUT.csv (the trajectory CSV to write)");
  engine::export_trajectory_csv(parsed.positionals().front(), out);
  return kExitOk;
}

int record_info(std::span<const std::string> args) {
  ArgParser parser("record info RUN.corsatraj",
                   "What a binary trajectory holds: step, recorded ticks, entities, roads.");
  parser.positional("RUN.corsatraj", "the binary trajectory");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const std::filesystem::path file = parsed.positionals().front();
  const engine::TrajectoryReader reader(file);
  std::cout << "file:          " << file.string() << " (" << std::filesystem::file_size(file)
            << " bytes)\n"
            << "step:          " << format_fixed(reader.dt(), 6) << " s, every " << reader.every()
            << " recorded\n"
            << "ticks:         " << reader.first_tick() << " to " << reader.last_tick() << ", "
            << reader.frame_count() << " recorded\n"
            << "entities:      " << reader.entity_count() << "\n"
            << "roads:         " << reader.road_count() << "\n";
  return kExitOk;
}

constexpr Action kActions[] = {
    {"export", "the trajectory CSV of the run, byte for byte (-o OUT.csv)", record_export},
    {"info", "step, recorded ticks, entities and roads of the file", record_info},
};

}  // namespace

int command_record(std::span<const std::string> args) {
  return run_action({.command = "record",
                     .synopsis = "ACTION RUN.corsatraj [options]",
                     .description = "Binary trajectories (corsa run --record FILE.corsatraj; "
                                    "docs/trajectory-format.md).",
                     .actions = kActions},
                    args);
}

}  // namespace corsa::cli
