// `corsa map mesh MAP.xodr -o map.obj|map.ply`: the road surface mesh for 3D viewers.

#include <filesystem>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "corsa/core/strings.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/mesh_io.h"
#include "corsa/xodr/road_mesh.h"
#include "map_actions.h"
#include "output_paths.h"

namespace corsa::cli {

int map_mesh(std::span<const std::string> args) {
  ArgParser parser("map mesh MAP.xodr -o FILE [options]",
                   "Triangulates every lane (all lane types) and the road marks and writes the "
                   "mesh as Wavefront OBJ (with a .mtl of the same name: groups and materials per "
                   "lane type and mark colour) or PLY (per-face lane type, kind, colour, road, "
                   "lane, junction flag). Map coordinates, metres, z up.");
  parser.positional("MAP.xodr", "the OpenDRIVE map");
  parser.option("-o", "FILE", "output mesh: .obj or .ply (required)");
  parser.option("--tolerance", "M",
                "largest distance from a lane border to the mesh (default 0.1)");
  parser.flag("--ascii", "PLY as text instead of binary");
  parser.flag("--no-marks", "lane surfaces only, without the road marks");
  parser.epilog("example:\n  corsa map mesh town.xodr -o town.ply --tolerance 0.05");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  const std::filesystem::path output = required_output_file(
      parsed, "-o", "FILE (the .obj or .ply to write)", [&parsed](const std::filesystem::path& p) {
        const std::string extension = corsa::to_lower(p.extension().string());
        if (extension != ".obj" && extension != ".ply") {
          throw UsageError("-o " + p.string() +
                           ": the mesh format comes from the extension, .obj or .ply");
        }
        if (parsed.flag("--ascii") && extension != ".ply") {
          throw UsageError("--ascii applies to .ply output only");
        }
      });
  const std::string extension = corsa::to_lower(output.extension().string());
  xodr::MeshOptions options;
  if (const auto tolerance = parsed.number("--tolerance")) {
    if (!(*tolerance >= 1e-4 && *tolerance <= 100.0)) {
      throw UsageError("--tolerance must be between 0.0001 and 100 (metres)");
    }
    options.tolerance = *tolerance;
  }
  options.road_marks = !parsed.flag("--no-marks");

  // Warnings go to stderr as they are found.
  corsa::Diagnostics diagnostics([](const corsa::Diagnostic& d) { std::cerr << d << '\n'; });
  const xodr::Map map = xodr::Map::load(parsed.positionals().at(0), diagnostics);
  const xodr::RoadMesh mesh = xodr::build_road_mesh(map, options, diagnostics);
  xodr::write_mesh(mesh, output,
                   parsed.flag("--ascii") ? xodr::PlyEncoding::kAscii : xodr::PlyEncoding::kBinary);

  size_t marks = 0;
  for (const xodr::TriangleInfo& info : mesh.info) {
    marks += info.kind == xodr::SurfaceKind::kRoadMark ? 1 : 0;
  }
  std::cout << "wrote " << output.string();
  if (extension == ".obj") {
    std::cout << " and " << std::filesystem::path(output).replace_extension(".mtl").string();
  }
  std::cout << ": " << mesh.triangles.size() << " triangles (" << marks << " road marks), "
            << mesh.vertices.size() << " vertices, tolerance "
            << corsa::format_double(options.tolerance) << " m\n";
  return kExitOk;
}

}  // namespace corsa::cli
