#include "commands.h"
#include "pending.h"

namespace corsa::cli {

int command_validate(std::span<const std::string> args) {
  ArgParser parser(
      "validate FILE... [--json]",
      "Checks OpenSCENARIO (.xosc) and OpenDRIVE (.xodr) files; prints file:line errors.");
  parser.positional("FILE", "files to check", 1, -1);
  return pending_command(parser, args, "validate");
}

}  // namespace corsa::cli
