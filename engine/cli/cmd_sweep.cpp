#include "commands.h"
#include "pending.h"

namespace corsa::cli {

int command_sweep(std::span<const std::string> args) {
  ArgParser parser("sweep DIST.xosc [options]",
                   "Runs the parameter variants of a distribution or a quick grid.");
  parser.positional("DIST.xosc", "ParameterValueDistribution or scenario file");
  return pending_command(parser, args, "sweep");
}

}  // namespace corsa::cli
