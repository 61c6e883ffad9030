// `corsa map holes MAP.xodr`: the holes in the map's junctions (xodr/junction_holes.h) that the
// sensor world paves or leaves as they are, with a summary line.

#include <iostream>
#include <map>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "corsa/core/strings.h"
#include "corsa/xodr/junction_holes.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/road_mesh.h"
#include "map_actions.h"

namespace corsa::cli {

int map_holes(std::span<const std::string> args) {
  ArgParser parser("map holes MAP.xodr [--list]",
                   "Finds the holes in the map's junctions: places inside a junction's area (its "
                   "<boundary>, or the hull of its connecting roads) that no lane covers but its "
                   "roads enclose on all sides. The sensor world paves the small or narrow ones "
                   "bordered only by the junction's roadway; islands (wide and large), holes "
                   "bordered by a kerb, sidewalk, median or another road, and holes with an "
                   "object or signal in them stay as they are. Prints a summary line.");
  parser.positional("MAP.xodr", "the OpenDRIVE map");
  parser.flag("--list", "also one CSV row per hole: junction,kind,area_m2,width_m,x,y,z");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  corsa::Diagnostics diagnostics([](const corsa::Diagnostic& d) { std::cerr << d << '\n'; });
  const xodr::Map map = xodr::Map::load(parsed.positionals().at(0), diagnostics);
  const xodr::RoadMesh mesh =
      xodr::build_road_mesh(map, xodr::MeshOptions{.road_marks = false}, diagnostics);
  const std::vector<xodr::JunctionHole> holes = xodr::find_junction_holes(map, mesh);

  std::ostringstream out;
  if (parsed.flag("--list")) {
    out << "junction,kind,area_m2,width_m,x,y,z\n";
    for (const xodr::JunctionHole& h : holes) {
      out << map.junction(h.junction).id << ',' << xodr::hole_kind_name(h.kind) << ','
          << corsa::format_fixed(h.area, 2) << ',' << corsa::format_fixed(h.width, 2) << ','
          << corsa::format_fixed(h.centre.x, 2) << ',' << corsa::format_fixed(h.centre.y, 2) << ','
          << corsa::format_fixed(h.centre.z, 2) << '\n';
    }
  }
  struct Tally {
    size_t count = 0;
    double area = 0.0;
  };
  std::map<xodr::HoleKind, Tally> by_kind;
  for (const xodr::JunctionHole& h : holes) {
    ++by_kind[h.kind].count;
    by_kind[h.kind].area += h.area;
  }
  out << "junction holes: " << holes.size();
  for (const xodr::HoleKind kind : {xodr::HoleKind::kPaved, xodr::HoleKind::kLarge,
                                    xodr::HoleKind::kKerbed, xodr::HoleKind::kOccupied}) {
    out << ", " << xodr::hole_kind_name(kind) << ' ' << by_kind[kind].count << " ("
        << corsa::format_fixed(by_kind[kind].area, 1) << " m2)";
  }
  out << '\n';
  std::cout << out.str();
  return kExitOk;
}

}  // namespace corsa::cli
