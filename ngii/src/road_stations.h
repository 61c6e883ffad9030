#pragma once

// Where a road's lanes are measured: the lanes' polylines in map coordinates (as surveyed,
// smoothed, and extended by the lanes before and after), and the stations along the fitted
// reference line where each lane crosses its normal (road_builder.h steps 1 and 3).

#include <vector>

#include "corsa/xodr/model.h"
#include "lane_tracker.h"
#include "polyline.h"
#include "reference_line.h"
#include "road_plan.h"

namespace corsa::ngii::detail {

/// The polylines of one road's lanes in map coordinates.
struct LaneLines {
  std::vector<Polyline> raw;           ///< as surveyed
  std::vector<Polyline> smooth;        ///< survey noise removed (what the lanes are fitted to)
  std::vector<Polyline> measured;      ///< smoothed, with a few metres before and after the lane
  std::vector<double> measured_start;  ///< arc length on `measured` where the lane starts
  /// The stretch of `measured` (arc lengths) a lane's direction is taken from (Crossing):
  /// a junction path's own stretch, the whole line for other roads. A path's lead-in and
  /// lead-out turn into the roads it joins, often at a corner of 10-30 degrees at the node;
  /// its end width is the joined lane's width times the cosine of the angle between the
  /// path's own end and that road (match_path_ends), so the road builder must divide by the
  /// cosine of the path's own angle there too, or the path's end is narrower (wider) than
  /// the lane it joins.
  std::vector<double> direction_from;
  std::vector<double> direction_to;
};

/// The lanes of `plan` (map coordinates: source minus `origin`).
LaneLines lane_lines(const RoadPlan& plan, const Origin& origin);

/// The measurements along the fitted reference line.
struct Stations {
  std::vector<double> s;
  std::vector<RefSample> ref;
  std::vector<double> curvature;                 ///< of the reference line, 1/m
  std::vector<std::vector<Crossing>> crossings;  ///< [lane][station]
};

/// Stations every `spacing` metres plus where each lane's vertices are (so that the widths
/// follow the lanes into sharp corners of coarsely digitised links), at least 0.2 m apart.
Stations measure_stations(const xodr::Road& road, const LaneLines& lines, double spacing);

/// Adds stations halfway between neighbours where a lane border (`border_t[station][border]`,
/// m) moves by more than 8 cm, so that the separately fitted laneOffset and widths cannot drift
/// apart between them. Returns whether any was added (the borders must then be solved again).
bool refine_stations(Stations& st, const std::vector<std::vector<double>>& border_t,
                     const xodr::Road& road, const LaneLines& lines);

/// Road s at which the lane's arc length reaches `target`, from the station measurements
/// (`u`: the lane's arc length at each of `stations`).
double s_at_u(const std::vector<double>& stations, const std::vector<double>& u, double target);

/// Whether station i of lane k is on the lane itself (not on its lead-in or lead-out), within
/// `margin` metres.
bool own_part(const Stations& st, const LaneLines& lines, size_t k, size_t i, double margin);

}  // namespace corsa::ngii::detail
