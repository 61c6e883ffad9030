#pragma once

// Coordinate reference system transforms through PROJ, for placing models (e.g. buildings
// published in WGS84) into the map's projected frame (e.g. UTM-K, EPSG:5179).

#include <memory>
#include <string>

#include "corsa/sensors/environment.h"
#include "corsa/sensors/geometry.h"

namespace corsa::sensors {

/// A transform between two CRSs, given as anything PROJ accepts ("EPSG:4326", a PROJ string,
/// WKT). Axis order is normalised to x = easting / longitude, y = northing / latitude (degrees
/// for geographic CRSs); z passes through (metres).
class CrsTransform {
 public:
  /// Throws corsa::InputError (message names both CRSs) when PROJ cannot build the transform.
  CrsTransform(const std::string& from, const std::string& to);
  ~CrsTransform();
  CrsTransform(CrsTransform&&) noexcept;
  CrsTransform& operator=(CrsTransform&&) noexcept;

  Vec3 apply(Vec3 p) const;
  /// True when the source CRS is geographic (x, y in degrees).
  bool source_is_geographic() const { return source_geographic_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool source_geographic_ = false;
};

/// Latitude and longitude of a map point, from the map's CRS.
GeoLocation geolocation_of(const std::string& map_crs, Vec3 map_point);

}  // namespace corsa::sensors
