// `corsa map ACTION ...`: dispatch to the map actions (map_actions.h).

#include "actions.h"
#include "commands.h"
#include "map_actions.h"

namespace corsa::cli {
namespace {

constexpr Action kActions[] = {
    {"info", "roads, junctions, lanes by type, lengths, geometry kinds, georeference", map_info},
    {"query", "road,s,t -> x,y,z,h (or x,y -> road,lane,s,t with --to-lane), CSV", map_query},
    {"render", "top-down picture of the map (PNG)", map_render},
    {"mesh", "road surface mesh (OBJ or PLY)", map_mesh},
    {"holes", "holes in junctions: paved by the sensor world or kept (islands), per kind",
     map_holes},
};

}  // namespace

int command_map(std::span<const std::string> args) {
  return run_action({.command = "map",
                     .synopsis = "ACTION MAP.xodr [options]",
                     .description = "Inspects an OpenDRIVE map.",
                     .actions = kActions},
                    args);
}

}  // namespace corsa::cli
