// `corsa map mesh`: placeholder until the road-mesh builder lands (that work replaces this
// file).

#include "args.h"
#include "map_actions.h"
#include "pending.h"

namespace corsa::cli {

int map_mesh(std::span<const std::string> args) {
  ArgParser parser("map mesh MAP.xodr -o map.obj",
                   "Writes the road surface mesh (not available yet).");
  parser.positional("MAP.xodr", "the map");
  parser.option("-o", "FILE", "output mesh (.obj or .ply)");
  return pending_command(parser, args, "map mesh");
}

}  // namespace corsa::cli
