#include "network.h"

#include <cmath>

#include "corsa/core/strings.h"
#include "polyline.h"

namespace corsa::ngii::detail {
namespace {

/// Links shorter than this (m) carry no lane: they are folded into their start node.
constexpr double kZeroLength = 0.1;
/// A link end farther than this (m) from its node is off the node.
constexpr double kNodeGap = 0.1;
/// Length attributes differing from the geometry by more than this (m) are reported.
constexpr double kLengthMismatch = 1.0;

/// Removes vertices where the line turns back on itself (more than kSpikeTurn between the
/// segments before and after), again until none is left: a digitising error that runs a link
/// back over its own path and forward again. Returns how many were removed.
constexpr double kSpikeTurn = 160.0 * M_PI / 180.0;

size_t remove_spikes(std::vector<Point3>& points) {
  size_t removed = 0;
  for (bool changed = true; changed && points.size() > 2;) {
    changed = false;
    for (size_t i = 1; i + 1 < points.size(); ++i) {
      const Vec2 a = xy(points[i]) - xy(points[i - 1]);
      const Vec2 b = xy(points[i + 1]) - xy(points[i]);
      if (norm(a) < 1e-9 || norm(b) < 1e-9) {
        continue;
      }
      const double turn = std::abs(angle_diff(std::atan2(b.y, b.x), std::atan2(a.y, a.x)));
      if (turn > kSpikeTurn) {
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(i));
        removed += 1 + remove_duplicates(points);
        changed = true;
        break;
      }
    }
  }
  return removed;
}

int find_root(std::vector<int>& alias, int node) {
  while (alias[static_cast<size_t>(node)] != node) {
    node = alias[static_cast<size_t>(node)] =
        alias[static_cast<size_t>(alias[static_cast<size_t>(node)])];
  }
  return node;
}

}  // namespace

Network::Network(const Layers& layers, CorrectionLog& log, Diagnostics& diagnostics)
    : layers_(layers) {
  for (size_t i = 0; i < layers.nodes.size(); ++i) {
    node_index_.emplace(layers.nodes[i].id, static_cast<int>(i));
  }
  node_alias_.resize(layers.nodes.size());
  for (size_t i = 0; i < node_alias_.size(); ++i) {
    node_alias_[i] = static_cast<int>(i);
  }
  links.resize(layers.links.size());
  for (size_t i = 0; i < layers.links.size(); ++i) {
    const Link& link = layers.links[i];
    link_index_.emplace(link.id, static_cast<int>(i));
    LinkState& state = links[i];
    state.points = link.points;
    state.lane_no = link.lane_no;
    // read_layers guarantees both nodes exist.
    state.from = node_index_.at(link.from_node);
    state.to = node_index_.at(link.to_node);
  }
  resolve_ids(log);
  clean_geometry(log, diagnostics);
  drop_zero_length(log);
  snap_ends(log);
  index_nodes();
}

std::optional<int> Network::find(std::string_view id) const {
  const auto it = link_index_.find(id);
  return it == link_index_.end() ? std::nullopt : std::optional<int>(it->second);
}

void Network::resolve_ids(CorrectionLog& log) {
  for (size_t i = 0; i < links.size(); ++i) {
    const Link& link = layers_.links[i];
    for (const bool right : {false, true}) {
      const std::string& id = right ? link.right_id : link.left_id;
      if (id.empty()) {
        continue;
      }
      const char* field = right ? "R_LinkID" : "L_LinkID";
      const auto target = find(id);
      if (!target) {
        log.add(static_cast<int>(i), field, id, "", "points to a link that does not exist");
      } else if (*target == static_cast<int>(i)) {
        log.add(static_cast<int>(i), field, id, "", "points to the link itself");
      } else {
        (right ? links[i].right : links[i].left) = *target;
      }
    }
  }
}

void Network::clean_geometry(CorrectionLog& log, Diagnostics& diagnostics) {
  size_t no_speed = 0;
  int first_no_speed = -1;
  for (size_t i = 0; i < links.size(); ++i) {
    LinkState& state = links[i];
    const size_t before = state.points.size();
    if (remove_duplicates(state.points) > 0) {
      log.add(static_cast<int>(i), "geometry", std::to_string(before) + " vertices",
              std::to_string(state.points.size()) + " vertices",
              "duplicate consecutive vertices removed");
    }
    const size_t with_spikes = state.points.size();
    if (const size_t spikes = remove_spikes(state.points); spikes > 0) {
      log.add(static_cast<int>(i), "geometry", std::to_string(with_spikes) + " vertices",
              std::to_string(state.points.size()) + " vertices",
              "the line turns back on itself (by more than 160 degrees) and forward again; "
              "those vertices removed");
    }
    state.length = Polyline(state.points).length();
    const Link& link = layers_.links[i];
    if (link.length_attr > 0.0 && std::abs(link.length_attr - state.length) > kLengthMismatch) {
      log.add(static_cast<int>(i), "Length", format_fixed(link.length_attr, 2),
              format_fixed(state.length, 2),
              "Length attribute differs from the geometry; the geometry length is used");
    }
    if (link.max_speed == 0 && no_speed++ == 0) {
      first_no_speed = static_cast<int>(i);
    }
  }
  if (no_speed > 0) {
    // A located note: 0 is how the data marks a missing limit, and none is written (nothing
    // is guessed).
    Diagnostic note = make_warning(layers_.link_file, 0,
                                   std::to_string(no_speed) +
                                       " link(s) have MaxSpeed 0 (missing): no speed limit is "
                                       "written for their lanes (the first is this one)");
    note.severity = Severity::kNote;
    note.record = layers_.links[static_cast<size_t>(first_no_speed)].record;
    diagnostics.add(std::move(note));
  }
}

void Network::drop_zero_length(CorrectionLog& log) {
  for (size_t i = 0; i < links.size(); ++i) {
    LinkState& state = links[i];
    if (state.length >= kZeroLength) {
      continue;
    }
    state.removed = true;
    const int from = find_root(node_alias_, state.from);
    const int to = find_root(node_alias_, state.to);
    node_alias_[static_cast<size_t>(to)] = from;
    log.add(static_cast<int>(i), "geometry", format_fixed(state.length, 3) + " m", "removed",
            "zero-length link: its end node " + layers_.links[i].to_node + " is merged into " +
                layers_.links[i].from_node);
  }
  for (LinkState& state : links) {
    state.from = find_root(node_alias_, state.from);
    state.to = find_root(node_alias_, state.to);
  }
}

void Network::snap_ends(CorrectionLog& log) {
  // Positions of every link end at each node, to tell a misplaced link end from a misplaced node.
  std::vector<std::vector<Vec2>> ends(layers_.nodes.size());
  for (const LinkState& state : links) {
    if (!state.removed) {
      ends[static_cast<size_t>(state.from)].push_back(xy(state.points.front()));
      ends[static_cast<size_t>(state.to)].push_back(xy(state.points.back()));
    }
  }
  for (size_t i = 0; i < links.size(); ++i) {
    LinkState& state = links[i];
    if (state.removed) {
      continue;
    }
    for (const bool at_end : {false, true}) {
      const int node = at_end ? state.to : state.from;
      const Vec2 target = xy(layers_.nodes[static_cast<size_t>(node)].position);
      const Vec2 end = xy(at_end ? state.points.back() : state.points.front());
      const double gap = norm(end - target);
      if (gap <= kNodeGap) {
        continue;
      }
      // Only move the link when another link end agrees with the node position.
      bool node_agreed = false;
      for (const Vec2& other : ends[static_cast<size_t>(node)]) {
        node_agreed = node_agreed || norm(other - target) <= kNodeGap;
      }
      if (!node_agreed) {
        continue;
      }
      const Polyline line(state.points);
      const Projection p = line.project(target);
      const Point3 node_point{target.x, target.y,
                              at_end ? state.points.back().z : state.points.front().z};
      // Past the end (or before the start): extend to the node; otherwise cut the link there.
      std::vector<Point3> moved;
      if (at_end) {
        const bool beyond = p.along > 0.0 || p.u > line.length() - 1e-6;
        moved = beyond ? state.points : line.slice(0.0, p.u);
        if (beyond) {
          moved.push_back(node_point);
        } else {
          moved.back() = node_point;
        }
      } else {
        const bool before = p.along < 0.0 || p.u < 1e-6;
        moved = before ? state.points : line.slice(p.u, line.length());
        if (before) {
          moved.insert(moved.begin(), node_point);
        } else {
          moved.front() = node_point;
        }
      }
      remove_duplicates(moved);
      state.points = std::move(moved);
      state.length = Polyline(state.points).length();
      log.add(static_cast<int>(i), "geometry",
              std::string(at_end ? "end" : "start") + " " + format_fixed(gap, 2) + " m from node " +
                  layers_.nodes[static_cast<size_t>(node)].id,
              "moved onto the node",
              "link end away from its node, where the other links at the node meet");
    }
  }
}

void Network::index_nodes() {
  starting.assign(layers_.nodes.size(), {});
  ending.assign(layers_.nodes.size(), {});
  for (size_t i = 0; i < links.size(); ++i) {
    if (!links[i].removed) {
      starting[static_cast<size_t>(links[i].from)].push_back(static_cast<int>(i));
      ending[static_cast<size_t>(links[i].to)].push_back(static_cast<int>(i));
    }
  }
}

}  // namespace corsa::ngii::detail
