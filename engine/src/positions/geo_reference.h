#pragma once

// GeoPosition support (OpenSCENARIO 1.3 §6.4 GeoPosition) through the map's geoReference
// (OpenDRIVE 1.8 §6.3): only the simple, common case is handled here, a transverse Mercator or
// UTM projection on the WGS84 / GRS80 ellipsoid, plus the header <offset>. Anything else is
// reported to the caller, which turns it into a located error.

#include <optional>
#include <string>
#include <string_view>

#include "corsa/xodr/model.h"

namespace corsa::engine::detail {

/// A transverse Mercator projection (UTM is one with fixed parameters).
struct TransverseMercator {
  double a = 6378137.0;            ///< ellipsoid semi-major axis, m
  double f = 1.0 / 298.257223563;  ///< flattening
  double lat0 = 0.0;               ///< rad
  double lon0 = 0.0;               ///< rad
  double k0 = 1.0;
  double x0 = 0.0;  ///< false easting, m
  double y0 = 0.0;  ///< false northing, m
};

/// Parses a PROJ string of the simple kind ("+proj=tmerc ..." or "+proj=utm +zone=N [+south]"
/// with +ellps/+datum WGS84 or GRS80). Nothing for anything else.
std::optional<TransverseMercator> parse_simple_projection(std::string_view proj);

/// Projects geographic coordinates (degrees) to easting/northing (m), Krüger's series to sixth
/// order in the third flattening (Karney 2011), accurate to well below a millimetre within the
/// usual zone widths.
struct EastNorth {
  double x = 0.0;
  double y = 0.0;
};
EastNorth project(const TransverseMercator& tm, double lat_deg, double lon_deg);

/// Map coordinates of a geographic point: projected, then moved into the file's frame by the
/// header <offset> (x_geo = offset + R(hdg) * x_file). Nothing when the geoReference is not a
/// simple projection.
std::optional<EastNorth> geo_to_map(const xodr::Header& header, double lat_deg, double lon_deg);

}  // namespace corsa::engine::detail
