#pragma once

// Figures of merit of a converted NGII map, computed from the raw A2/B2 layers and the map as
// written (its lanes found through their <userData code="ngii:link"> provenance), never from the
// converter's own intermediate data:
// - where each lane starts and ends against its A2 link's first and last vertex, and the gaps
//   between lanes joined in the lane graph (end of one, start of the next), and unpaved wedges
//   and slivers just beyond the joined lane ends (mouth_gaps.h);
// - the vertical error of each lane: the map's road surface under each A2 vertex along it
//   against the vertex's height (p95 per lane), and the same against the lane centre's height
//   level with the vertex (which counts a cross slope as error where a link leaves its lane's
//   centre, as a lane splitting off its neighbour does);
// - the lane width against the B2 marks bounding the lane (R_linkID / L_linkID name it);
// - pairs of A2 links that the survey names as neighbours (L/R link ids) and that run side by
//   side along >= 90% of both, but which the map still keeps in different roads;
// - the roads whose mesh folds over itself (mesh_folds.h);
// - gaps between opposing roads where a B2 centre mark pairs them (centre_gaps.h);
// - centre strips touching end to end without a lane-graph join (strip_joins.h).
// Used by the tests and by the `corsa_ngii_measure` program (docs/ngii.md).

#include <string>
#include <vector>

#include "centre_gaps.h"
#include "corsa/ngii/layers.h"
#include "corsa/xodr/map.h"
#include "mouth_gaps.h"
#include "strip_joins.h"

namespace corsa::test {

struct GapFigures {
  size_t count = 0;   ///< measured ends
  size_t over = 0;    ///< ends farther than the limit (0.2 m)
  double max = 0.0;   ///< m
  std::string worst;  ///< what the largest one is (link id, or road/lane)
};

struct NgiiFigures {
  GapFigures link_ends;  ///< lane start/end vs its A2 link's first/last vertex
  /// Link ends at a lane split or merge (the link starts or ends at a node shared with another
  /// ordinary link): the lane there has zero width at its neighbour's edge, half a lane width
  /// from the node.
  GapFigures split_ends;
  GapFigures lane_joins;  ///< lane end vs the start of each lane-graph successor
  /// Joins at a lane split or merge: the ordinary A2 link after (before) the join starts (ends)
  /// at a node where another ordinary link starts (ends) too. The new lane begins beside its
  /// neighbour (at zero width at the road's edge), while its link begins at the shared node
  /// inside that neighbour.
  GapFigures split_joins;
  MouthGapFigures mouth_gaps;  ///< unpaved runs just beyond joined lane ends (mouth_gaps.h)
  size_t lanes_measured = 0;
  /// p95 over every A2 vertex of its distance from its lane's centre line in the map (m), of
  /// the vertices whose foot lies inside that line and within 1 m (as for the heights).
  double lateral_p95 = 0.0;
  /// Largest per-lane p95 of |z map - z A2| (m), the map's surface under the A2 vertex.
  double vertical_p95_max = 0.0;
  double vertical_max = 0.0;   ///< largest single vertex error (m)
  size_t lanes_over_5cm = 0;   ///< lanes whose p95 exceeds 5 cm
  std::string vertical_worst;  ///< link id of the worst lane
  /// The same against the lane centre's height level with the vertex (up to 1 m beside it).
  double vertical_centre_p95_max = 0.0;
  size_t lanes_centre_over_5cm = 0;
  std::string vertical_centre_worst;
  size_t width_samples = 0;
  double width_p95 = 0.0;         ///< p95 |width map - width between B2 marks| (m), all lanes
  double width_p95_single = 0.0;  ///< the same on roads with one lane
  size_t side_by_side_pairs = 0;  ///< neighbour pairs beside each other along >= 90%
  size_t split_pairs = 0;         ///< of those, kept in different roads
  std::vector<std::string> split_examples;
  size_t lanes_without_provenance = 0;
  size_t links_without_lane = 0;  ///< A2 links (longer than 0.1 m) no lane names
  size_t folded_roads = 0;        ///< roads whose mesh folds over itself (mesh_folds.h)
  CentreGapFigures centre_gaps;   ///< strips between opposing roads (centre_gaps.h)
  StripJoinFigures strip_joins;   ///< centre strips continuing into each other (strip_joins.h)
};

/// Measures `map` against `layers` (the map's header offset places it in the layers' CRS).
NgiiFigures measure_ngii(const ngii::Layers& layers, const xodr::Map& map);

/// The figures as "name value" lines.
std::string format_figures(const NgiiFigures& f);

}  // namespace corsa::test
