#include "corsa/sensors/georeference.h"

namespace corsa::sensors {

GeoLocation geolocation_of(const std::string& map_crs, Vec3 map_point) {
  const CrsTransform to_wgs84(map_crs, "EPSG:4326");
  const Vec3 g = to_wgs84.apply(map_point);
  return {g.y, g.x};
}

}  // namespace corsa::sensors
