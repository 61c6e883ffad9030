// `corsa map render MAP.xodr -o map.png`: the top-down picture (in the plugin: it needs OpenCV).

#include <filesystem>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "corsa/core/strings.h"
#include "corsa/render/map_render.h"
#include "corsa/xodr/map.h"
#include "output_paths.h"
#include "plugin_commands.h"

namespace corsa::cli {
namespace {

int map_render_body(std::span<const std::string> args) {
  ArgParser parser("map render MAP.xodr -o FILE.png [options]",
                   "Draws the map from above for people: lanes filled by type (driving grey, "
                   "sidewalks light, shoulders and borders paler, junctions tinted), road marks "
                   "in their colours, a scale bar and a north arrow (+y up).");
  parser.positional("MAP.xodr", "the OpenDRIVE map");
  parser.option("-o", "FILE", "output picture, .png (required)");
  parser.option("--size", "PX",
                "pixels along the longer side (default 2048, " +
                    std::to_string(render::kMinPictureSide) + ".." +
                    std::to_string(render::kMaxPictureSide) + ")");
  parser.option("--scale", "M_PER_PX", "metres per pixel instead of --size");
  parser.flag("--road-ids", "write each road's id at its middle (not inside junctions)");
  parser.epilog("example:\n  corsa map render town.xodr -o town.png --size 4096 --road-ids");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const std::filesystem::path output = required_output_file(
      parsed, "-o", "FILE.png (the picture to write)", [](const std::filesystem::path& p) {
        if (corsa::to_lower(p.extension().string()) != ".png") {
          throw UsageError("-o " + p.string() + ": the picture is written as PNG; name it .png");
        }
      });
  render::RenderOptions options;
  const auto size = parsed.integer("--size");
  const auto scale = parsed.number("--scale");
  if (size && scale) {
    throw UsageError("give --size or --scale, not both");
  }
  if (size) {
    if (*size < render::kMinPictureSide || *size > render::kMaxPictureSide) {
      throw UsageError("--size must be between " + std::to_string(render::kMinPictureSide) +
                       " and " + std::to_string(render::kMaxPictureSide) + " pixels");
    }
    options.size = static_cast<int>(*size);
  }
  if (scale) {
    if (!(*scale > 0.0 && *scale <= 1e6)) {
      throw UsageError("--scale must be a positive number of metres per pixel");
    }
    options.scale = *scale;
  }
  options.road_ids = parsed.flag("--road-ids");

  corsa::Diagnostics diagnostics([](const corsa::Diagnostic& d) { std::cerr << d << '\n'; });
  const xodr::Map map = xodr::Map::load(parsed.positionals().at(0), diagnostics);
  const render::MapPicture picture = render::render_map(map, options, diagnostics);
  render::write_png(picture, output);
  std::cout << "wrote " << output.string() << ": " << picture.width << " x " << picture.height
            << " pixels, " << corsa::format_fixed(picture.scale, 3) << " m per pixel\n";
  return kExitOk;
}

}  // namespace

int plugin_map_render(std::span<const std::string> args) {
  return guarded("map render", map_render_body, args);
}

}  // namespace corsa::cli
