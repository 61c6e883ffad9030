#include "commands.h"
#include "pending.h"

namespace corsa::cli {

int command_run(std::span<const std::string> args) {
  ArgParser parser(
      "run SCENARIO.xosc [options]",
      "Runs one OpenSCENARIO scenario headless with a fixed step and writes its outputs.");
  parser.positional("SCENARIO.xosc", "the scenario to run");
  return pending_command(parser, args, "run");
}

}  // namespace corsa::cli
