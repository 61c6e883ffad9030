#pragma once

// Map's private state (shared by the map_*.cpp files).

#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"
#include "pose_table.h"
#include "span_table.h"
#include "spatial_index.h"

namespace corsa::xodr {

namespace detail {

/// Road and junction ids -> indices.
struct IdIndex {
  std::unordered_map<std::string, size_t> road_by_id;
  std::unordered_map<std::string, size_t> junction_by_id;
};

/// Puts records that a file listed out of s order in order (stable), warning once per kind.
void sort_map_records(MapData& data, corsa::Diagnostics& diagnostics);
/// Checks references, record order, lengths and joints (warnings/errors); fills the id maps.
void validate_map(const MapData& data, IdIndex& ids, corsa::Diagnostics& diagnostics,
                  const BuildOptions& options);
/// Builds the lane graph of a validated map.
LaneGraph build_lane_graph(const Map& map, corsa::Diagnostics& diagnostics);

}  // namespace detail

struct Map::Impl {
  MapData data;
  detail::IdIndex ids;
  /// What a road pose reads (planView records with their headings' cos/sin, laneOffset,
  /// elevation, superelevation), packed from `data`.
  detail::PoseTable poses;
  LaneGraph graph;
  /// The lane sections packed for lane spans (lane_span_in_section), made from `data`.
  detail::SpanTable spans;
  /// Prepared by the first world -> lane query (Map::locate), not by Map::build: most runs never
  /// ask one (lane positions and lane following need none). Preparing is cheap (a bound per
  /// lane section); each section's chunks are built when a query first reaches it, so a run
  /// that locates a few points does not pay for the whole map. call_once makes the first query
  /// safe from concurrent threads (a sweep shares one Map between its variants); sections are
  /// built under their own once flags.
  mutable std::once_flag index_built;
  mutable detail::SpatialIndex index;
};

}  // namespace corsa::xodr
