// `corsa map info MAP.xodr`: a summary of a map (roads, junctions, lanes by type, lengths,
// geometry kinds, georeference) after a full load, so its warnings are listed too.

#include <iostream>
#include <map>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "corsa/core/strings.h"
#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "map_actions.h"

namespace corsa::cli {
namespace {

std::string metres(double value) { return corsa::format_fixed(value, 1) + " m"; }

void print_roads(std::ostream& out, const xodr::Map& map) {
  size_t in_junction = 0;
  size_t sections = 0;
  size_t signals = 0;
  size_t objects = 0;
  double length = 0.0;
  std::map<std::string, size_t> kinds;
  for (const xodr::Road& road : map.data().roads) {
    in_junction += road.in_junction() ? 1 : 0;
    sections += road.lane_sections.size();
    signals += road.signals.size();
    objects += road.objects.size();
    length += road.length;
    for (const xodr::Geometry& geometry : road.plan_view) {
      ++kinds[xodr::geometry_kind_name(geometry.shape)];
    }
  }
  out << "roads:         " << map.road_count() << " (" << in_junction
      << " in junctions), reference lines " << metres(length) << '\n';
  out << "geometry:     ";
  for (const auto& [kind, count] : kinds) {
    out << ' ' << kind << ' ' << count;
  }
  out << '\n';
  out << "lane sections: " << sections << '\n';
  out << "signals:       " << signals << ", objects " << objects << '\n';
}

void print_junctions(std::ostream& out, const xodr::Map& map) {
  const char* names[] = {"default", "direct", "virtual", "crossing"};
  size_t by_type[4] = {0, 0, 0, 0};
  size_t connections = 0;
  for (const xodr::Junction& junction : map.data().junctions) {
    ++by_type[static_cast<int>(junction.type)];
    connections += junction.connections.size();
  }
  out << "junctions:     " << map.junction_count();
  for (int i = 0; i < 4; ++i) {
    if (by_type[i] > 0) {
      out << ", " << names[i] << ' ' << by_type[i];
    }
  }
  out << " (" << connections << " connections)\n";
}

void print_lanes(std::ostream& out, const xodr::Map& map) {
  struct Tally {
    size_t count = 0;
    double length = 0.0;
  };
  std::map<std::string, Tally> by_type;
  double total = 0.0;
  const xodr::LaneGraph& graph = map.lane_graph();
  for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
    const auto& info = graph.info(node);
    const xodr::Lane* lane = map.lane(info.lane);
    const std::string name = lane->type == xodr::LaneType::kOther
                                 ? lane->type_name
                                 : std::string(xodr::lane_type_name(lane->type));
    Tally& tally = by_type[name];
    ++tally.count;
    tally.length += info.length;
    total += info.length;
  }
  out << "lanes:         " << graph.size() << " (per lane section), total length " << metres(total)
      << '\n';
  for (const auto& [name, tally] : by_type) {
    out << "  " << name << std::string(name.size() < 15 ? 15 - name.size() : 1, ' ') << tally.count
        << ", " << metres(tally.length) << '\n';
  }
  out << "lane links:    " << graph.join_count() << '\n';
}

void print_header(std::ostream& out, const xodr::Map& map, const std::string& file) {
  const xodr::Header& h = map.data().header;
  out << "map:           " << file << '\n';
  out << "OpenDRIVE:     " << h.rev_major << '.' << h.rev_minor;
  if (!h.vendor.empty()) {
    out << ", vendor " << h.vendor;
  }
  if (!h.name.empty()) {
    out << ", name " << h.name;
  }
  out << '\n';
  out << "bounds:        west " << corsa::format_fixed(h.west, 1) << ", east "
      << corsa::format_fixed(h.east, 1) << ", south " << corsa::format_fixed(h.south, 1)
      << ", north " << corsa::format_fixed(h.north, 1) << '\n';
  out << "georeference:  " << (h.geo_reference.empty() ? "(none)" : h.geo_reference) << '\n';
  if (h.offset_x != 0.0 || h.offset_y != 0.0 || h.offset_z != 0.0 || h.offset_hdg != 0.0) {
    out << "offset:        x " << corsa::format_double(h.offset_x) << ", y "
        << corsa::format_double(h.offset_y) << ", z " << corsa::format_double(h.offset_z)
        << ", hdg " << corsa::format_double(h.offset_hdg) << '\n';
  }
}

}  // namespace

int map_info(std::span<const std::string> args) {
  ArgParser parser("map info MAP.xodr",
                   "Loads a map and summarises it: roads, junctions, lanes by type with their "
                   "lengths, geometry kinds, georeference, and the load's warnings.");
  parser.positional("MAP.xodr", "the OpenDRIVE map");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const std::string file = parsed.positionals().at(0);
  // Warnings go to stderr as they are found; the summary counts them.
  corsa::Diagnostics diagnostics([](const corsa::Diagnostic& d) { std::cerr << d << '\n'; });
  const xodr::Map map = xodr::Map::load(file, diagnostics);
  std::ostringstream out;
  print_header(out, map, file);
  print_roads(out, map);
  print_junctions(out, map);
  print_lanes(out, map);
  out << "warnings:      " << diagnostics.count(corsa::Severity::kWarning) << '\n';
  std::cout << out.str();
  return kExitOk;
}

}  // namespace corsa::cli
