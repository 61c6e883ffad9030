#pragma once

// GeoPosition support (OpenSCENARIO 1.3 §6.4 GeoPosition) through the map's geoReference
// (OpenDRIVE 1.8 §6.3): PROJ projects the geographic point into the geoReference's CRS (through
// SimulationOptions::geo_projection, see corsa/geo/crs_transform.h), and the header <offset>
// moves it into the file's frame.

#include <optional>

#include "corsa/core/vec.h"
#include "corsa/xodr/model.h"

namespace corsa::engine::detail {

struct SimState;

/// Map coordinates (m) of a geographic point (degrees): projected into the geoReference's CRS,
/// then moved into the file's frame by the header <offset> (x_geo = offset + R(hdg) * x_file).
/// Nothing where the CRS gives no finite result. Throws corsa::InputError (unlocated, saying
/// why) when the map has no geoReference, the run has no transform, or PROJ cannot read it.
std::optional<Vec2> geo_to_map(const SimState& state, const xodr::Header& header, double lat_deg,
                               double lon_deg);

}  // namespace corsa::engine::detail
