#pragma once

// NGII HD road layers -> OpenDRIVE MapData: correction of the lane attributes, grouping of the
// lane links into roads, fitting of reference lines and lane widths, junctions, road marks and
// signals. The result is written with corsa::xodr::write_xodr and loads with xodr::Map::build.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/layers.h"
#include "corsa/xodr/model.h"

namespace corsa::ngii {

struct ConvertOptions {
  /// Largest distance (m) between the reference polyline and the fitted plan view.
  double tolerance = 0.05;
  /// Largest error (m) of the fitted laneOffset and lane width polynomials at the stations.
  double width_tolerance = 0.02;
  /// Largest error (m) of the fitted elevation profile (at the reference line).
  double elevation_tolerance = 0.02;
  /// Largest height error (m) the fitted superelevation may add at the outermost lane centre.
  double superelevation_tolerance = 0.015;
  /// Width (m) of a lane with no B2 marks, no neighbour and no lane before or after it to
  /// measure against (counted in ConversionSummary::fallback_widths, with a warning).
  double fallback_lane_width = 3.25;
  /// Spacing (m) of the stations where lane offsets are measured.
  double station_spacing = 1.0;
  /// Width (m) of a sidewalk lane added on the outer (right) edge of every road that has no
  /// lane beside it there (NGII has no sidewalks; pedestrians need somewhere to walk); 0: none.
  double sidewalk_width = 0.0;
  /// A connecting road may be fed by several incoming roads, one <connection> each (OpenDRIVE
  /// 1.8 §12.4): lanes side by side in a junction stay one road though they come from different
  /// roads. False keeps every connecting road to one <connection> (OpenDRIVE 1.7 §10.3), as
  /// output for older readers needs (`corsa convert ngii --compat 1.4`).
  bool several_incoming_roads = true;
  /// Called as the conversion advances: fraction done in [0, 1]. Optional.
  std::function<void(double)> progress;
};

/// Whether a change is a repair of bad source data or only a relabelling that follows from how
/// the converter grouped the lanes (the source was not wrong).
enum class CorrectionKind : uint8_t {
  kDefect,   ///< the source data breaks its own rules here (a located note names the record)
  kRelabel,  ///< renumbered to fit the converted roads (e.g. a road split off a lateral group
             ///< restarts its LaneNo at 1); listed, no note
};

/// One change of the source data: which link, which field, the value before and after, and why.
struct Correction {
  std::string link_id;
  std::string field;  ///< DBF field name (LaneNo, L_LinkID, R_LinkID) or "geometry"
  std::string old_value;
  std::string new_value;
  std::string reason;
  int64_t record = -1;  ///< A2_LINK record number
  CorrectionKind kind = CorrectionKind::kDefect;
};

/// Where one A2 link ended up: a lane of a road over an s range. A link may appear in several
/// places (a junction path shared by several connecting roads, or a road cut in two).
struct LinkPlacement {
  std::string link_id;
  std::string road_id;
  int section = 0;  ///< lane section index within the road
  int lane_id = 0;
  double s_start = 0.0;  ///< road s where the link starts (m)
  double s_end = 0.0;
};

struct ConversionSummary {
  size_t links_read = 0;
  size_t links_dropped = 0;  ///< zero-length links merged into their nodes
  size_t roads = 0;          ///< all roads, connecting roads included
  size_t connecting_roads = 0;
  size_t lanes = 0;
  size_t junctions = 0;         ///< default junctions (intersections)
  size_t direct_junctions = 0;  ///< splits and merges of ordinary lanes (OpenDRIVE 1.8 §10.5)
  size_t corrections = 0;       ///< all rows of the corrections report
  size_t defects = 0;           ///< of those, repairs of bad source data (the rest relabel)
  size_t geometries = 0;        ///< planView records
  size_t road_marks = 0;
  size_t signals = 0;
  size_t controllers = 0;  ///< signal controllers (one per intersection approach)
  size_t structures = 0;   ///< tunnel and bridge records (A2 RoadType 2-5)
  size_t sidewalks = 0;    ///< sidewalk lanes added (ConvertOptions::sidewalk_width)
  size_t signs = 0;        ///< B1 safety signs (static signals)
  size_t objects = 0;      ///< objects from B3, C3, C4, C6, A4, A5
  /// ordinary roads given a restricted lane over the strip between double centre lines
  size_t centre_strips = 0;
  /// shoulder lanes paving the ground beside a lane that continues into a narrower one
  size_t mouth_fills = 0;
  /// Lanes by where their width came from: B2 marks, L/R neighbour spacing, the lanes before
  /// and after them, the fallback width.
  size_t widths_from_marks = 0;
  size_t widths_from_neighbours = 0;
  size_t widths_from_topology = 0;
  size_t fallback_widths = 0;
  int kinks = 0;  ///< heading jumps where a link turns too sharply for a smooth fit
  /// Largest distance (m) between a lane centre line and its source link polyline at the
  /// measuring stations (survey noise included), the same against the noise-filtered lines
  /// the lanes were fitted to, and between a reference polyline and its fitted plan view.
  double max_lane_error = 0.0;
  double max_smoothed_error = 0.0;
  double max_reference_error = 0.0;
};

struct Conversion {
  xodr::MapData map;
  std::vector<Correction> corrections;
  std::vector<LinkPlacement> placements;
  ConversionSummary summary;
};

/// Converts read layers. Data faults are repaired and reported (corrections, and one located
/// note per repair naming the A2 record, Severity::kNote); faults that cannot be repaired throw
/// corsa::InputError. What is left uncertain (no width to measure, a mark type OpenDRIVE lacks)
/// is a warning.
Conversion convert(const Layers& layers, const ConvertOptions& options,
                   corsa::Diagnostics& diagnostics);

/// The corrections as CSV: header `link_id,field,old_value,new_value,reason,record,kind`
/// (kind: `defect` or `relabel`), quoted where needed (RFC 4180).
std::string corrections_csv(const std::vector<Correction>& corrections);

/// Writes corrections_csv atomically. Throws InputError on I/O failure.
void write_corrections_csv(const std::vector<Correction>& corrections,
                           const std::filesystem::path& path);

/// Where each A2 link ended up, as CSV: header `link_id,road_id,lane_section,lane_id,s_start,
/// s_end` (s in metres along the road), one row per placement in road order.
std::string placements_csv(const std::vector<LinkPlacement>& placements);

/// Writes placements_csv atomically. Throws InputError on I/O failure.
void write_placements_csv(const std::vector<LinkPlacement>& placements,
                          const std::filesystem::path& path);

}  // namespace corsa::ngii
