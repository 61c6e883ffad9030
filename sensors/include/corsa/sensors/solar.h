#pragma once

#include <optional>

namespace corsa::sensors {

/// Where the sun is: azimuth clockwise from north and elevation above the horizon, radians (the
/// convention of OpenSCENARIO 1.2 Sun). Geometric elevation: no atmospheric refraction.
struct SolarPosition {
  double azimuth = 0.0;
  double elevation = 0.0;
};

/// Solar position from the NOAA solar calculator equations (Meeus, "Astronomical Algorithms",
/// as used in NOAA's spreadsheet; accurate to about 0.01 degree for years 1901-2099).
/// `local_seconds` since local midnight, `utc_offset_hours` = local time - UTC; latitude and
/// longitude in degrees (east positive). Without an offset the time is local apparent solar
/// time at the place: 12:00 is the sun's transit (its highest), whatever the longitude.
SolarPosition solar_position(int year, int month, int day, double local_seconds,
                             std::optional<double> utc_offset_hours, double latitude_deg,
                             double longitude_deg);

}  // namespace corsa::sensors
