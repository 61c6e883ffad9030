#pragma once

// Coordinate reference system transforms through PROJ: between the map's projected frame (e.g.
// UTM-K, EPSG:5179, or the transverse Mercator of an OpenDRIVE geoReference) and the Earth
// (WGS84 latitude and longitude), or between any two CRSs PROJ knows. The one place Corsa turns
// map coordinates into Earth coordinates and back; nothing here is hand-written projection math.

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "corsa/core/vec.h"

namespace corsa::geo {

/// A transform between two CRSs, given as anything PROJ accepts ("EPSG:4326", a PROJ string,
/// WKT). Axis order is normalised to x = easting / longitude, y = northing / latitude (degrees
/// for geographic CRSs); z passes through (metres). A PROJ string without "+type=crs" (as
/// OpenDRIVE geoReferences are written) is read as the CRS it describes.
class CrsTransform {
 public:
  /// Throws corsa::InputError (message names both CRSs) when PROJ cannot build the transform.
  CrsTransform(const std::string& from, const std::string& to);
  ~CrsTransform();
  CrsTransform(CrsTransform&&) noexcept;
  CrsTransform& operator=(CrsTransform&&) noexcept;

  /// Throws corsa::InputError when the point is outside the valid area of the CRS.
  Vec3 apply(Vec3 p) const;
  /// Nothing when the point is outside the valid area of the CRS.
  std::optional<Vec3> try_apply(Vec3 p) const;
  /// True when the source CRS is geographic (x, y in degrees).
  bool source_is_geographic() const { return source_geographic_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool source_geographic_ = false;
};

/// WGS84 latitude and longitude (degrees) to x, y in a projected CRS (metres east and north for
/// the usual ones); nothing where PROJ gives no finite result. Copyable, and safe to call from
/// one thread at a time (each copy shares one PROJ context).
using GeographicToProjected =
    std::function<std::optional<Vec2>(double latitude_deg, double longitude_deg)>;

/// PROJ's GeographicToProjected for `crs` (an OpenDRIVE geoReference: a PROJ string, WKT or
/// "EPSG:n"). Throws corsa::InputError with PROJ's reason when PROJ cannot build it.
GeographicToProjected geographic_to_projected(const std::string& crs);

}  // namespace corsa::geo
