// The conversion pipeline: repair, group, plan, fit, assemble, decorate, georeference.

#include "corsa/ngii/convert.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "assemble.h"
#include "centre_gaps.h"
#include "correction_log.h"
#include "corsa/core/strings.h"
#include "decorations.h"
#include "feature_layers.h"
#include "lane_numbers.h"
#include "lateral.h"
#include "mouth_fills.h"
#include "network.h"
#include "network_plan.h"
#include "strip_links.h"

namespace corsa::ngii {
namespace {

using namespace detail;

/// The local origin: the centre of the links' extent, rounded to 100 m so that it reads well
/// in the header and map coordinates stay small (and doubles keep sub-micrometre precision).
Origin choose_origin(const Layers& layers) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Link& link : layers.links) {
    for (const Point3& p : link.points) {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
  }
  return Origin{std::round(0.5 * (x0 + x1) / 100.0) * 100.0,
                std::round(0.5 * (y0 + y1) / 100.0) * 100.0};
}

void check_options(const ConvertOptions& options) {
  if (!(options.tolerance > 0.0) || !(options.width_tolerance > 0.0) ||
      !(options.elevation_tolerance > 0.0) || !(options.superelevation_tolerance > 0.0) ||
      !(options.fallback_lane_width > 0.0) || !(options.station_spacing > 0.0) ||
      !(options.sidewalk_width >= 0.0)) {
    throw std::invalid_argument("ngii::convert: tolerances, widths and spacing must be > 0");
  }
}

xodr::Header make_header(const Layers& layers, const Origin& origin,
                         const std::vector<xodr::Road>& roads) {
  xodr::Header header;
  header.name = layers.dir.filename().string();
  if (header.name.empty()) {
    header.name = layers.dir.parent_path().filename().string();
  }
  header.vendor = "Corsa (NGII HD map conversion)";
  header.geo_reference = layers.crs.proj_string;
  // Map coordinates + offset = coordinates in the geoReference CRS (model.h, §2.6 / §6.4).
  header.offset_x = origin.x;
  header.offset_y = origin.y;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const xodr::Road& road : roads) {
    for (const xodr::Geometry& g : road.plan_view) {
      x0 = std::min(x0, g.x);
      y0 = std::min(y0, g.y);
      x1 = std::max(x1, g.x);
      y1 = std::max(y1, g.y);
    }
  }
  if (!roads.empty()) {
    header.west = x0;
    header.south = y0;
    header.east = x1;
    header.north = y1;
  }
  return header;
}

}  // namespace

Conversion convert(const Layers& layers, const ConvertOptions& options, Diagnostics& diagnostics) {
  check_options(options);
  const auto progress = [&](double done) {
    if (options.progress) {
      options.progress(done);
    }
  };
  CorrectionLog log(layers, diagnostics);
  Network network(layers, log, diagnostics);
  repair_neighbours(network, log);
  const LateralStructure lateral = lateral_structure(network);
  correct_lane_numbers(network, lateral, log);
  progress(0.05);
  const NetworkPlan plan =
      plan_network(network, lateral, options.several_incoming_roads, diagnostics);
  progress(0.1);
  const Origin origin = choose_origin(layers);
  Assembly assembly = assemble(plan, network, origin, options, diagnostics);

  Conversion result;
  result.map.roads = std::move(assembly.roads);
  result.map.junctions = std::move(assembly.junctions);
  result.placements = std::move(assembly.placements);
  result.summary = assembly.summary;
  const Decorations decorations =
      decorate(result.map, result.placements, layers, origin, diagnostics);
  result.summary.road_marks = decorations.road_marks;
  result.summary.signals = decorations.signals;
  result.summary.controllers = decorations.controllers;
  result.summary.structures = decorations.structures;
  const FeatureCounts features = place_features(result.map, result.placements, layers, origin);
  result.summary.signs = features.signals;
  result.summary.objects = features.objects;
  result.summary.structures += features.structures;
  // After the decorations, which index a road's lanes from its centre lane.
  result.summary.centre_strips = close_centre_gaps(result.map.roads, result.placements, layers);
  link_centre_strips(result.map);
  // After the strips, so that a fill on the left lies beyond a road's strip.
  result.summary.mouth_fills = fill_lane_mouths(result.map);
  result.map.header = make_header(layers, origin, result.map.roads);
  result.summary.links_read = layers.links.size();
  for (const LinkState& link : network.links) {
    result.summary.links_dropped += link.removed;
  }
  if (result.summary.fallback_widths > 0) {
    diagnostics.add(make_warning(
        layers.link_file, 0,
        std::to_string(result.summary.fallback_widths) +
            " lane(s) have no B2 marks, no neighbour and no lane before or after them to measure "
            "their width against; " +
            format_fixed(options.fallback_lane_width, 2) + " m is used"));
  }
  result.corrections = log.take();
  result.summary.corrections = result.corrections.size();
  for (const Correction& c : result.corrections) {
    result.summary.defects += c.kind == CorrectionKind::kDefect;
  }
  progress(1.0);
  return result;
}

}  // namespace corsa::ngii
