#pragma once

// The lane-link network being repaired: per link its cleaned geometry, its (repaired) neighbour
// and lane-number attributes and its end nodes, with the links starting and ending at each node.
// Built from the layers by Network::build, which also makes the geometric repairs (duplicate
// vertices, zero-length links, link ends away from their node).

#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "correction_log.h"
#include "corsa/ngii/layers.h"

namespace corsa::ngii::detail {

struct LinkState {
  std::vector<Point3> points;  ///< cleaned polyline (no consecutive duplicates)
  int left = -1;               ///< repaired L_LinkID as a link index, -1 for none
  int right = -1;              ///< repaired R_LinkID
  int lane_no = 0;             ///< corrected LaneNo
  int from = -1;               ///< start node (index into layers.nodes, merged aliases resolved)
  int to = -1;
  bool removed = false;  ///< a zero-length link folded into its node
  double length = 0.0;   ///< geometry length (m)
};

class Network {
 public:
  Network(const Layers& layers, CorrectionLog& log, Diagnostics& diagnostics);

  const Layers& layers() const { return layers_; }
  const Link& source(int link) const { return layers_.links[static_cast<size_t>(link)]; }
  bool is_junction(int link) const { return source(link).link_type == "1"; }
  size_t size() const { return links.size(); }
  std::optional<int> find(std::string_view id) const;
  /// Rebuilds `starting` / `ending` from the links' nodes (after edits).
  void index_nodes();

  std::vector<LinkState> links;
  std::vector<std::vector<int>> starting;  ///< per node: links starting there (not removed)
  std::vector<std::vector<int>> ending;    ///< per node: links ending there

 private:
  void resolve_ids(CorrectionLog& log);
  void clean_geometry(CorrectionLog& log, Diagnostics& diagnostics);
  void drop_zero_length(CorrectionLog& log);
  void snap_ends(CorrectionLog& log);

  const Layers& layers_;
  std::unordered_map<std::string_view, int> link_index_;
  std::unordered_map<std::string_view, int> node_index_;
  std::vector<int> node_alias_;  ///< merged node -> representative
};

}  // namespace corsa::ngii::detail
