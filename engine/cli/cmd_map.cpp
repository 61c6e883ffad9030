#include "commands.h"
#include "pending.h"

namespace corsa::cli {

int command_map(std::span<const std::string> args) {
  ArgParser parser("map {info|query|render|mesh} MAP.xodr [options]", "Inspects an OpenDRIVE map.");
  parser.positional("ACTION MAP.xodr", "what to do, and the map", 2, 2);
  return pending_command(parser, args, "map");
}

}  // namespace corsa::cli
