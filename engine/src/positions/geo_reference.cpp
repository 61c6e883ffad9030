#include "positions/geo_reference.h"

#include <cmath>
#include <string>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

[[noreturn]] void unavailable(const std::string& message) {
  throw InputError(make_error("", 0, message));
}

const GeographicToMap& projection_of(const SimState& state, const xodr::Header& header) {
  if (!state.geo_to_map) {
    const std::string crs(trim(header.geo_reference));
    if (crs.empty()) {
      unavailable("the map has no geoReference, which GeoPosition needs");
    }
    if (!state.options.geo_projection) {
      unavailable(
          "GeoPosition needs a map-to-Earth transform, and this run was given none "
          "(SimulationOptions::geo_projection, e.g. corsa::geo::geographic_to_projected)");
    }
    state.geo_to_map = state.options.geo_projection(crs);
  }
  return *state.geo_to_map;
}

}  // namespace

std::optional<Vec2> geo_to_map(const SimState& state, const xodr::Header& header, double lat_deg,
                               double lon_deg) {
  const auto geo = projection_of(state, header)(lat_deg, lon_deg);
  if (!geo) {
    return std::nullopt;
  }
  // OpenDRIVE <offset>: x_geo = offset + R(hdg) x_file, so x_file = R(-hdg) (x_geo - offset).
  const double dx = geo->x - header.offset_x;
  const double dy = geo->y - header.offset_y;
  const double c = std::cos(header.offset_hdg);
  const double s = std::sin(header.offset_hdg);
  return Vec2{c * dx + s * dy, -s * dx + c * dy};
}

}  // namespace corsa::engine::detail
