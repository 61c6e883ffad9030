#include "commands.h"
#include "pending.h"

namespace corsa::cli {

int command_convert(std::span<const std::string> args) {
  ArgParser parser("convert ngii DIR -o OUT.xodr [options]",
                   "Converts NGII HD road layers (Shapefile + DBF) to OpenDRIVE.");
  parser.positional("ngii DIR", "source format and folder", 2, 2);
  return pending_command(parser, args, "convert");
}

}  // namespace corsa::cli
