#pragma once

// Shared helpers of the OpenDRIVE tests: where the real maps are, loading them.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/xodr/map.h"

namespace corsa::xodr::test {

inline std::filesystem::path shared_map(const std::string& name) {
  return std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr" / name;
}

/// The 19 maps of ../shared/data/xodr and the 6 of the ASAM OpenSCENARIO 1.3 conformance set.
inline std::vector<std::filesystem::path> all_shared_maps() {
  std::vector<std::filesystem::path> maps;
  for (const auto* dir : {"data/xodr", "conformance/asam-osc-1.3/Databases"}) {
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(CORSA_SHARED_DIR) / dir)) {
      if (entry.path().extension() == ".xodr") {
        maps.push_back(entry.path());
      }
    }
  }
  std::sort(maps.begin(), maps.end());
  return maps;
}

inline Map load_map(const std::filesystem::path& path) {
  corsa::Diagnostics diagnostics;
  return Map::load(path, diagnostics);
}

/// A road built in memory: one geometry, `lanes_per_side` driving lanes of `width` each side.
inline Road make_road(const std::string& id, GeometryShape shape, double length,
                      int lanes_per_side = 1, double width = 3.0) {
  Road road;
  road.id = id;
  road.length = length;
  Geometry geometry;
  geometry.length = length;
  geometry.shape = shape;
  road.plan_view.push_back(geometry);
  LaneSection section;
  for (int id_ = lanes_per_side; id_ >= -lanes_per_side; --id_) {
    Lane lane;
    lane.id = id_;
    lane.type = id_ == 0 ? LaneType::kNone : LaneType::kDriving;
    lane.type_name = id_ == 0 ? "none" : "driving";
    if (id_ != 0) {
      lane.widths.push_back(Poly3{0.0, width, 0.0, 0.0, 0.0});
    }
    section.lanes.push_back(lane);
  }
  road.lane_sections.push_back(section);
  return road;
}

}  // namespace corsa::xodr::test
