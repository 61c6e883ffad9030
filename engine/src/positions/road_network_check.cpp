#include "corsa/engine/road_network_check.h"

#include <algorithm>
#include <filesystem>

#include "corsa/xodr/parser.h"
#include "positions/position_common.h"

namespace corsa::engine {
namespace {

/// One reference against the map, by the functions that place entities in a run (in their
/// order); throws the InputError a run would stop with, warns as a run would.
void check_road_reference(bool strict, Diagnostics& diagnostics, const xodr::Map& map,
                          const xosc::RoadReference& reference) {
  const uint32_t road = detail::need_road(map, reference.road_id, reference.source);
  const double s = detail::checked_s(strict, diagnostics, map, road, reference.s, reference.source);
  if (!reference.lane_id) {
    return;
  }
  const int lane = detail::parse_lane_id(*reference.lane_id, reference.source, true);
  if (lane != 0) {
    detail::need_lane_center(map, road, s, lane, reference.source);
  }
}

}  // namespace

std::vector<Diagnostic> MapReferenceCheck::check(const xosc::RoadNetwork& network,
                                                 const std::vector<xosc::RoadReference>& references,
                                                 Diagnostics& diagnostics) const {
  std::vector<Diagnostic> errors;
  if (references.empty()) {
    return errors;
  }
  if (!network.logic_file || network.logic_file_path.empty()) {
    for (const auto& reference : references) {
      errors.push_back(
          reference.source.error(std::string(reference.kind) +
                                 " needs a road network, but the scenario has no LogicFile"));
    }
    return errors;
  }
  std::error_code missing;
  if (!std::filesystem::is_regular_file(network.logic_file_path, missing)) {
    return errors;  // reported where the LogicFile is read
  }
  try {
    const xodr::Map map = xodr::Map::load(network.logic_file_path, diagnostics);
    if (strict_) {
      try {
        xodr::refuse_lenient_readings(map.data());
      } catch (const InputError& error) {
        errors = error.diagnostics();
      }
    }
    for (const auto& reference : references) {
      try {
        check_road_reference(strict_, diagnostics, map, reference);
      } catch (const InputError& error) {
        errors.insert(errors.end(), error.diagnostics().begin(), error.diagnostics().end());
      }
    }
  } catch (const InputError& error) {
    return error.diagnostics();
  }
  return errors;
}

}  // namespace corsa::engine
