#pragma once

// Where the map lies on the Earth, for the sun's position: map coordinates to latitude and
// longitude through PROJ (corsa/geo/crs_transform.h, which also places models, e.g. buildings
// published in WGS84, into the map's projected frame).

#include <string>

#include "corsa/geo/crs_transform.h"
#include "corsa/sensors/environment.h"
#include "corsa/sensors/geometry.h"

namespace corsa::sensors {

using geo::CrsTransform;

/// Latitude and longitude of a map point, from the map's CRS.
GeoLocation geolocation_of(const std::string& map_crs, Vec3 map_point);

}  // namespace corsa::sensors
