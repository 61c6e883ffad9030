// `corsa convert ngii DIR -o OUT.xodr [--tolerance M] [--report FILE] [--placements FILE]
// [--compat 1.4] [--sidewalks W] [--verbose] [--strict] [--quiet]`: NGII HD road layers to
// OpenDRIVE (in the plugin: the import needs PROJ and shapelib). Thin: arguments, progress,
// printing; the work is corsa::ngii (ngii/).

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/writer.h"
#include "output_paths.h"
#include "plugin_commands.h"

namespace corsa::cli {
namespace {

/// Warnings printed before "... and N more". Repairs of source defects are located notes, not
/// warnings: one line counts them (--verbose prints each, --report lists each, --strict refuses
/// them).
constexpr size_t kWarningsShown = 20;

ArgParser make_parser() {
  ArgParser parser("convert ngii DIR -o OUT.xodr [options]",
                   "Converts NGII HD road layers (A1_NODE, A2_LINK and, when present, "
                   "B2_SURFACELINEMARK and C1_TRAFFICLIGHT; Shapefile + DBF) to OpenDRIVE 1.8: "
                   "lane numbers and neighbours repaired, lanes grouped into roads, reference "
                   "lines fitted with lines, arcs and clothoids, widths from the lane marks, "
                   "elevation and superelevation from the lanes' heights, junctions, road marks, "
                   "signals with their controllers, tunnels and bridges.");
  parser.positional("ngii DIR",
                    "the source format (ngii) and the folder of the layers, or the "
                    "path of its A2_LINK.shp",
                    2, 2);
  parser.option("-o", "OUT.xodr", "the OpenDRIVE file to write (required)");
  parser.option("--tolerance", "M",
                "largest distance of the fitted reference line from the "
                "lane data, metres (default 0.05)");
  parser.option("--report", "FILE",
                "write every change of the source data as CSV "
                "(link_id,field,old_value,new_value,reason,record,kind; kind: defect or "
                "relabel)");
  parser.option("--placements", "FILE",
                "write where each A2 link ended up as CSV "
                "(link_id,road_id,lane_section,lane_id,s_start,s_end)");
  parser.option("--compat", "VERSION",
                "write for readers of an older OpenDRIVE: 1.4 (no direct junctions, one lane "
                "predecessor/successor); default 1.8");
  parser.option("--sidewalks", "W",
                "add sidewalk lanes W metres wide on the free outer edge of every road "
                "(0.5-10)");
  parser.flag("--verbose",
              "print every located note (each repaired source defect with its A2 record)");
  parser.flag("--strict",
              "refuse source defects: every repair the conversion would make is an error "
              "(exit 2, nothing written)");
  parser.flag("--quiet", "no progress bar, warnings, notes or summary");
  parser.epilog("example:\n  corsa convert ngii data/kcity -o kcity.xodr --report kcity-fixes.csv");
  return parser;
}

/// The first kWarningsShown warnings; the notes (repaired source defects, skipped empty records)
/// each with `verbose`, else one line counting them.
void print_diagnostics(const Diagnostics& diagnostics, bool verbose) {
  size_t shown = 0;
  size_t hidden = 0;
  size_t notes = 0;
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.severity == Severity::kError) {
      continue;
    }
    if (d.severity == Severity::kNote) {
      ++notes;
      if (verbose) {
        std::cerr << d << '\n';
      }
      continue;
    }
    if (shown < kWarningsShown) {
      std::cerr << d << '\n';
      ++shown;
    } else {
      ++hidden;
    }
  }
  if (hidden > 0) {
    std::cerr << "... and " << hidden << " more warnings\n";
  }
  if (notes > 0 && !verbose) {
    std::cerr << "note: " << notes
              << " located notes (source defects repaired or left out, each with its record; "
                 "--verbose prints them, --report lists every repair, --strict refuses them)\n";
  }
}

/// With --strict: the notes of reading and converting (each a repaired source defect, or data
/// left out: a record without geometry, a mark of type "other", a missing speed limit) as one
/// InputError, before anything is written.
void refuse_repairs(const Diagnostics& diagnostics) {
  std::vector<Diagnostic> errors;
  for (Diagnostic d : diagnostics.all()) {
    if (d.severity == Severity::kNote) {
      d.severity = Severity::kError;
      d.message += " (refused by --strict)";
      errors.push_back(std::move(d));
    }
  }
  if (!errors.empty()) {
    throw InputError(std::move(errors));
  }
}

void print_summary(const ngii::ConversionSummary& s, const std::string& output) {
  std::cout << "converted " << s.links_read << " links -> " << s.roads << " roads ("
            << s.connecting_roads << " connecting), " << s.lanes << " lanes, " << s.junctions
            << " junctions + " << s.direct_junctions << " splits/merges, " << s.road_marks
            << " road marks, " << s.signals << " signals (" << s.controllers << " controllers), "
            << s.structures << " tunnels/bridges, " << s.signs << " signs, " << s.objects
            << " objects";
  if (s.sidewalks > 0) {
    std::cout << ", " << s.sidewalks << " sidewalks";
  }
  if (s.centre_strips > 0) {
    std::cout << ", " << s.centre_strips << " centre strips";
  }
  if (s.mouth_fills > 0) {
    std::cout << ", " << s.mouth_fills << " mouth fills";
  }
  std::cout << "; lane widths from marks " << s.widths_from_marks << ", neighbours "
            << s.widths_from_neighbours << ", lanes before/after " << s.widths_from_topology
            << ", fallback " << s.fallback_widths << "; " << s.corrections << " corrections ("
            << s.defects << " source defects, " << s.corrections - s.defects
            << " relabelled); largest fit error " << format_fixed(s.max_lane_error, 3)
            << " m (lane centres), " << format_fixed(s.max_reference_error, 3)
            << " m (reference lines), " << s.geometries << " planView records, " << s.kinks
            << " kinks -> " << output << '\n';
}

int convert_body(std::span<const std::string> args) {
  const ArgParser parser = make_parser();
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  if (parsed.positionals().at(0) != "ngii") {
    throw UsageError("unknown source format '" + parsed.positionals().at(0) +
                     "' (supported: ngii)");
  }
  const std::filesystem::path output =
      required_output_file(parsed, "-o", "OUT.xodr (the OpenDRIVE file to write)");
  ngii::ConvertOptions options;
  if (const auto tolerance = parsed.number("--tolerance")) {
    if (!(*tolerance >= 0.001 && *tolerance <= 1.0)) {
      throw UsageError("--tolerance must be between 0.001 and 1 metre");
    }
    options.tolerance = *tolerance;
  }
  if (const auto sidewalks = parsed.number("--sidewalks")) {
    if (!(*sidewalks >= 0.5 && *sidewalks <= 10.0)) {
      throw UsageError("--sidewalks must be between 0.5 and 10 metres");
    }
    options.sidewalk_width = *sidewalks;
  }
  xodr::WriteOptions write_options;
  if (const auto compat = parsed.value("--compat")) {
    if (*compat == "1.4") {
      write_options = xodr::compat_options(4);
      options.several_incoming_roads = false;  // one <connection> per connecting road (1.7)
    } else if (*compat != "1.8") {
      throw UsageError("--compat takes 1.4 (or 1.8, the default), not '" + *compat + "'");
    }
  }
  const bool quiet = parsed.flag("--quiet");
  const bool verbose = parsed.flag("--verbose");
  const std::optional<std::filesystem::path> report = output_file(parsed, "--report");
  const std::optional<std::filesystem::path> placements = output_file(parsed, "--placements");

  Diagnostics diagnostics;
  ngii::Conversion conversion;
  {
    ProgressBar progress("converting", 1.0, !quiet);
    options.progress = [&progress](double done) { progress.update(0.1 + 0.8 * done); };
    const ngii::Layers layers = ngii::read_layers(parsed.positionals().at(1), diagnostics);
    progress.update(0.1);
    conversion = ngii::convert(layers, options, diagnostics);
    if (parsed.flag("--strict")) {
      refuse_repairs(diagnostics);
    }
    // The map must load in Corsa: checked here rather than found by the next user.
    xodr::Map::build(conversion.map, diagnostics);
    progress.update(0.95);
    xodr::write_xodr(conversion.map, output, write_options);
    if (report) {
      ngii::write_corrections_csv(conversion.corrections, *report);
    }
    if (placements) {
      ngii::write_placements_csv(conversion.placements, *placements);
    }
    progress.finish();
  }
  if (!quiet) {
    print_diagnostics(diagnostics, verbose);
    print_summary(conversion.summary, output.string());
    if (report) {
      std::cout << "corrections: " << report->string() << '\n';
    }
    if (placements) {
      std::cout << "placements: " << placements->string() << '\n';
    }
  }
  return kExitOk;
}

}  // namespace

int plugin_convert(std::span<const std::string> args) {
  return guarded("convert", convert_body, args);
}

}  // namespace corsa::cli
