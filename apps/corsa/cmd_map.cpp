// `corsa map ACTION ...`: dispatch to the map actions (map_actions.h).

#include <iostream>

#include "args.h"
#include "commands.h"
#include "map_actions.h"

namespace corsa::cli {
namespace {

struct MapAction {
  const char* name;
  const char* summary;
  int (*run)(std::span<const std::string> args);
};

constexpr MapAction kActions[] = {
    {"info", "roads, junctions, lanes by type, lengths, geometry kinds, georeference", map_info},
    {"query", "road,s,t -> x,y,z,h (or x,y -> road,lane,s,t with --to-lane), CSV", map_query},
    {"render", "top-down picture of the map (PNG)", map_render},
    {"mesh", "road surface mesh (OBJ or PLY)", map_mesh},
};

void print_help(std::ostream& out) {
  out << "usage: corsa map ACTION MAP.xodr [options]\n\nInspects an OpenDRIVE map.\n\nactions:\n";
  for (const MapAction& action : kActions) {
    out << "  " << action.name << std::string(8 - std::string(action.name).size(), ' ')
        << action.summary << '\n';
  }
  out << "\n  corsa map ACTION --help   options of one action\n";
}

}  // namespace

int command_map(std::span<const std::string> args) {
  if (args.empty()) {
    print_help(std::cerr);
    return kExitBadInput;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    print_help(std::cout);
    return kExitOk;
  }
  for (const MapAction& action : kActions) {
    if (args[0] == action.name) {
      return action.run(args.subspan(1));
    }
  }
  throw UsageError("unknown map action '" + args[0] + "' (info, query, render, mesh)");
}

}  // namespace corsa::cli
