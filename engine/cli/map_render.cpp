// `corsa map render`: placeholder until the renderer lands (it belongs to the road-mesh/render
// work, which replaces this file).

#include "args.h"
#include "map_actions.h"
#include "pending.h"

namespace corsa::cli {

int map_render(std::span<const std::string> args) {
  ArgParser parser("map render MAP.xodr -o map.png",
                   "Draws the map from above (not available yet).");
  parser.positional("MAP.xodr", "the map");
  parser.option("-o", "FILE", "output picture");
  return pending_command(parser, args, "map render");
}

}  // namespace corsa::cli
