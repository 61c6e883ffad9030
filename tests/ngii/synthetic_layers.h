// NGII layers built in code for tests: nodes, links and lane marks placed in metres around an
// origin in the projected frame, at one height.

#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "corsa/ngii/convert.h"

namespace corsa::ngii::testing {

struct SyntheticLayers {
  Layers layers;
  double x0, y0, z;

  SyntheticLayers(double origin_x, double origin_y, double height)
      : x0(origin_x), y0(origin_y), z(height) {
    layers.node_file = "A1_NODE.dbf";
    layers.link_file = "A2_LINK.dbf";
    layers.mark_file = "B2_SURFACELINEMARK.dbf";
  }
  Point3 at(double x, double y) const { return {x0 + x, y0 + y, z}; }
  void node(const std::string& id, double x, double y) {
    layers.nodes.push_back(Node{.id = id,
                                .node_type = "99",
                                .position = at(x, y),
                                .record = static_cast<int64_t>(layers.nodes.size())});
  }
  /// A straight link from node a to node b (both added before), vertices a metre apart.
  void link(const std::string& id, const std::string& type, int lane_no, const std::string& a,
            const std::string& b, const std::string& right = "", const std::string& left = "") {
    Point3 pa{}, pb{};
    for (const Node& n : layers.nodes) {
      pa = n.id == a ? n.position : pa;
      pb = n.id == b ? n.position : pb;
    }
    std::vector<Point3> points;
    const double length = std::hypot(pb.x - pa.x, pb.y - pa.y);
    const int steps = static_cast<int>(std::ceil(length));
    for (int i = 0; i <= steps; ++i) {
      const double f = static_cast<double>(i) / steps;
      points.push_back({pa.x + f * (pb.x - pa.x), pa.y + f * (pb.y - pa.y), z});
    }
    add_link(id, type, lane_no, a, b, right, left, length, std::move(points));
  }
  /// A link through the given points (x, y), from node a to node b.
  void link_through(const std::string& id, int lane_no, const std::string& a, const std::string& b,
                    const std::vector<std::pair<double, double>>& xy, const std::string& right = "",
                    const std::string& left = "") {
    std::vector<Point3> points;
    double length = 0.0;
    for (size_t i = 0; i < xy.size(); ++i) {
      points.push_back(at(xy[i].first, xy[i].second));
      if (i > 0) {
        length += std::hypot(xy[i].first - xy[i - 1].first, xy[i].second - xy[i - 1].second);
      }
    }
    add_link(id, "6", lane_no, a, b, right, left, length, std::move(points));
  }
  /// A junction path (LinkType 1) through the given points (x, y), from node a to node b.
  void path_through(const std::string& id, const std::string& a, const std::string& b,
                    const std::vector<std::pair<double, double>>& xy) {
    link_through(id, 1, a, b, xy);
    layers.links.back().link_type = "1";
  }
  /// A white lane line through the given points (x, y) with `right` on its right and `left` on
  /// its left.
  void mark_through(const std::string& id, const std::vector<std::pair<double, double>>& xy,
                    const std::string& right, const std::string& left) {
    std::vector<Point3> points;
    for (const auto& [x, y] : xy) {
      points.push_back(at(x, y));
    }
    layers.marks.push_back(SurfaceMark{.id = id,
                                       .type = "211",
                                       .kind = "503",
                                       .right_link = right,
                                       .left_link = left,
                                       .points = std::move(points),
                                       .record = static_cast<int64_t>(layers.marks.size())});
  }
  /// A white lane line from (x0, y) to (x1, y) with `right` on its right and `left` on its left.
  void mark(const std::string& id, double from_x, double to_x, double y, const std::string& right,
            const std::string& left) {
    layers.marks.push_back(SurfaceMark{.id = id,
                                       .type = "211",
                                       .kind = "503",
                                       .right_link = right,
                                       .left_link = left,
                                       .points = {at(from_x, y), at(to_x, y)},
                                       .record = static_cast<int64_t>(layers.marks.size())});
  }

 private:
  void add_link(const std::string& id, const std::string& type, int lane_no, const std::string& a,
                const std::string& b, const std::string& right, const std::string& left,
                double length, std::vector<Point3> points) {
    layers.links.push_back(Link{.id = id,
                                .link_type = type,
                                .road_rank = "",
                                .road_type = "1",
                                .road_no = "",
                                .lane_no = lane_no,
                                .max_speed = 0,
                                .right_id = right,
                                .left_id = left,
                                .from_node = a,
                                .to_node = b,
                                .length_attr = length,
                                .points = std::move(points),
                                .record = static_cast<int64_t>(layers.links.size())});
  }
};

}  // namespace corsa::ngii::testing
