// libFuzzer target: any bytes as an OpenDRIVE document, read by Corsa's own XML reader
// (xodr/src/xml_dom.cpp), parsed into MapData and built into a Map (reference checks, lane graph,
// spatial index). Bad input must end in corsa::InputError, never a crash, a hang or a sanitizer
// report.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  corsa::Diagnostics diagnostics;
  try {
    auto map_data = corsa::xodr::parse_xodr_text(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.xodr", diagnostics);
    const auto map = corsa::xodr::Map::build(std::move(map_data), diagnostics);
    // A few queries on what was built, so that a Map that builds but is inconsistent shows up.
    std::vector<corsa::xodr::LaneSpan> spans;
    for (size_t road = 0; road < map.road_count() && road < 4; ++road) {
      const double length = map.road(road).length;
      for (double s : {0.0, 0.5 * length, length}) {
        const auto pose = map.world_pose(road, s, 0.0);
        map.lane_spans(road, s, spans);
        (void)map.locate(pose.x, pose.y);
      }
    }
  } catch (const corsa::InputError&) {
    // Expected for bad input.
  }
  return 0;
}
