// The figures of ngii_measure.h as "name value" lines (the corsa_ngii_measure program's output).

#include <sstream>

#include "ngii_measure.h"

namespace corsa::test {

std::string format_figures(const NgiiFigures& f) {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed;
  out << "link_ends_measured " << f.link_ends.count << "\n"
      << "link_ends_over_0.2m " << f.link_ends.over << "\n"
      << "link_ends_max_m " << f.link_ends.max << " (" << f.link_ends.worst << ")\n"
      << "split_merge_ends " << f.split_ends.count << " (over 0.2 m " << f.split_ends.over
      << ", max " << f.split_ends.max << ")\n"
      << "lane_joins_measured " << f.lane_joins.count << "\n"
      << "lane_joins_over_0.2m " << f.lane_joins.over << "\n"
      << "lane_joins_max_m " << f.lane_joins.max << " (" << f.lane_joins.worst << ")\n"
      << "mouth_gaps " << f.mouth_gaps.over << " of " << f.mouth_gaps.ends
      << " joined lane ends (max " << f.mouth_gaps.max << ", " << f.mouth_gaps.worst << ")\n"
      << "split_merge_joins " << f.split_joins.count << " (over 0.2 m " << f.split_joins.over
      << ", max " << f.split_joins.max << ")\n"
      << "lanes_measured " << f.lanes_measured << "\n"
      << "lateral_p95_m " << f.lateral_p95 << "\n"
      << "vertical_p95_max_m " << f.vertical_p95_max << " (" << f.vertical_worst << ")\n"
      << "vertical_max_m " << f.vertical_max << "\n"
      << "lanes_vertical_p95_over_5cm " << f.lanes_over_5cm << "\n"
      << "vertical_centre_p95_max_m " << f.vertical_centre_p95_max << " ("
      << f.vertical_centre_worst << ")\n"
      << "lanes_vertical_centre_p95_over_5cm " << f.lanes_centre_over_5cm << "\n"
      << "width_samples " << f.width_samples << "\n"
      << "width_p95_m " << f.width_p95 << "\n"
      << "width_p95_single_lane_roads_m " << f.width_p95_single << "\n"
      << "side_by_side_pairs " << f.side_by_side_pairs << "\n"
      << "side_by_side_split " << f.split_pairs;
  for (const auto& e : f.split_examples) {
    out << " " << e;
  }
  out << "\n"
      << "lanes_without_provenance " << f.lanes_without_provenance << "\n"
      << "links_without_lane " << f.links_without_lane << "\n"
      << "folded_roads " << f.folded_roads << "\n"
      << "centre_gap_stations " << f.centre_gaps.stations << " (over 5 cm " << f.centre_gaps.over
      << ", max " << f.centre_gaps.max << " at " << f.centre_gaps.worst << ")\n"
      << "centre_strip_joins " << f.strip_joins.joined << " of " << f.strip_joins.touching
      << " touching pairs (" << f.strip_joins.strip_ends << " strip ends; first unjoined: "
      << (f.strip_joins.unjoined.empty() ? "none" : f.strip_joins.unjoined) << ")\n"
      << "centre_strip_join_outer_gap_max_m " << f.strip_joins.outer_gap_max << " ("
      << f.strip_joins.outer_worst << ")\n";
  return out.str();
}

}  // namespace corsa::test
