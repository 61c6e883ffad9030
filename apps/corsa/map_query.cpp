// `corsa map query MAP.xodr [--in FILE] [--to-lane]`: CSV in, CSV out, full double precision.
//   default:    road,s,t  ->  x,y,z,h   (road by its id; h is the reference-line heading)
//   --to-lane:  x,y[,z]   ->  road,lane,s,t  (empty fields when no lane is within reach; with z,
//               stacked roads resolve to the one at that height)
// Blank lines and lines starting with '#' are skipped. The whole input is checked before
// anything is printed, so a bad line gives `file:line: error: ...`, exit 2 and no output.

#include <array>
#include <iostream>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/input_file.h"
#include "corsa/core/strings.h"
#include "corsa/xodr/map.h"
#include "map_actions.h"

namespace corsa::cli {
namespace {

/// Longest query line (bytes): a query is three numbers; this bounds what one line may hold.
constexpr size_t kMaxQueryLine = 4096;

struct Input {
  std::string name;
  std::istream* stream = nullptr;
};

[[noreturn]] void bad_line(const Input& input, int line, const std::string& message) {
  throw corsa::InputError(corsa::make_error(input.name, line, message));
}

std::vector<double> numbers(const Input& input, int line,
                            const std::vector<std::string_view>& fields, size_t first) {
  std::vector<double> values;
  for (size_t i = first; i < fields.size(); ++i) {
    const auto value = corsa::parse_double(fields[i]);
    if (!value) {
      bad_line(input, line, "'" + corsa::clip(corsa::trim(fields[i])) + "' is not a number");
    }
    values.push_back(*value);
  }
  return values;
}

std::string road_to_world(const xodr::Map& map, const Input& input, int line,
                          const std::vector<std::string_view>& fields) {
  if (fields.size() != 3) {
    bad_line(input, line, "expected road,s,t");
  }
  const std::string id(corsa::trim(fields[0]));
  const auto road = map.find_road(id);
  if (!road) {
    bad_line(input, line, "no road '" + id + "' in the map");
  }
  const auto v = numbers(input, line, fields, 1);
  const double length = map.road(*road).length;
  if (v[0] < 0.0 || v[0] > length) {
    bad_line(input, line,
             "s=" + corsa::format_double(v[0]) + " is outside road '" + id + "' (0.." +
                 corsa::format_double(length) + ")");
  }
  const xodr::WorldPose pose = map.world_pose(*road, v[0], v[1]);
  return corsa::format_double(pose.x) + ',' + corsa::format_double(pose.y) + ',' +
         corsa::format_double(pose.z) + ',' + corsa::format_double(pose.h);
}

std::string world_to_lane(const xodr::Map& map, const Input& input, int line,
                          const std::vector<std::string_view>& fields,
                          const xodr::LocateOptions& options) {
  if (fields.size() != 2 && fields.size() != 3) {
    bad_line(input, line, "expected x,y or x,y,z");
  }
  const auto v = numbers(input, line, fields, 0);
  xodr::LocateOptions at = options;
  if (v.size() == 3) {
    at.z = v[2];
  }
  const auto position = map.locate(v[0], v[1], at);
  if (!position) {
    return ",,,";
  }
  return map.road(position->road).id + ',' + std::to_string(position->lane) + ',' +
         corsa::format_double(position->s) + ',' + corsa::format_double(position->t);
}

}  // namespace

int map_query(std::span<const std::string> args) {
  ArgParser parser(
      "map query MAP.xodr [--in FILE] [--to-lane]",
      "Evaluates positions on the map, one CSV line per query (stdin by default):\n"
      "  road,s,t -> x,y,z,h        (road id, metres; heading in radians)\n"
      "  x,y[,z] -> road,lane,s,t   (with --to-lane; empty fields off the map; z picks\n"
      "                              the level where roads are stacked)");
  parser.positional("MAP.xodr", "the OpenDRIVE map");
  parser.option("--in", "FILE", "read queries from FILE instead of stdin");
  parser.flag("--to-lane", "world x,y[,z] -> road,lane,s,t");
  parser.option("--max-distance", "M", "with --to-lane: farthest a point may be from a lane (5)");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  corsa::Diagnostics diagnostics([](const corsa::Diagnostic& d) { std::cerr << d << '\n'; });
  const xodr::Map map = xodr::Map::load(parsed.positionals().at(0), diagnostics);
  xodr::LocateOptions options;
  options.max_distance = parsed.number("--max-distance").value_or(options.max_distance);
  if (options.max_distance < 0.0) {
    throw UsageError("--max-distance must not be negative");
  }
  // A query file is read whole (a regular file of bounded size, see read_file); standard input
  // is read line by line, each line bounded, so that no input runs memory out.
  std::istringstream file;
  Input input{"<stdin>", &std::cin};
  if (const auto path = parsed.value("--in")) {
    file.str(corsa::read_file(*path));
    input = Input{*path, &file};
  }
  const bool to_lane = parsed.flag("--to-lane");
  std::string out;
  std::array<char, kMaxQueryLine + 1> buffer{};
  int line = 0;
  uint64_t bytes = 0;
  while (input.stream->getline(buffer.data(), buffer.size())) {
    ++line;
    bytes += static_cast<uint64_t>(input.stream->gcount());
    if (bytes > corsa::kMaxInputBytes) {
      bad_line(input, line,
               "more than " + std::to_string(corsa::kMaxInputBytes >> 20) +
                   " MiB of queries (the output is held until all are read)");
    }
    const std::string_view trimmed = corsa::trim(buffer.data());
    if (trimmed.empty() || trimmed.front() == '#') {
      continue;
    }
    const auto fields = corsa::split(trimmed, ',');
    out += to_lane ? world_to_lane(map, input, line, fields, options)
                   : road_to_world(map, input, line, fields);
    out += '\n';
  }
  if (!input.stream->eof()) {
    throw corsa::InputError(corsa::make_error(
        input.name, line + 1,
        "line longer than " + std::to_string(kMaxQueryLine) + " bytes (one query per line)"));
  }
  std::cout << out;
  return kExitOk;
}

}  // namespace corsa::cli
