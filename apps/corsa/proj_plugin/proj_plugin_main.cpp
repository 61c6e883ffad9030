// libcorsa_proj.so: PROJ's transform from WGS84 into a map's geoReference, for the GeoPositions
// of `corsa run`, `sweep` and `test` (see ../plugin_api.h for why it is a module of its own).

#include <exception>

#include "corsa/core/diagnostic.h"
#include "corsa/geo/crs_transform.h"
#include "plugin_api.h"

namespace corsa::cli {
namespace {

engine::GeographicToMap geographic_to_map(const std::string& geo_reference, std::string& error) {
  try {
    return geo::geographic_to_projected(geo_reference);
  } catch (const InputError& e) {
    error = e.diagnostic().message;
  } catch (const std::exception& e) {
    error = e.what();
  }
  return {};
}

const ProjPluginApi kApi{kPluginAbiVersion, geographic_to_map};

}  // namespace
}  // namespace corsa::cli

extern "C" __attribute__((visibility("default"))) const corsa::cli::ProjPluginApi*
corsa_proj_plugin_api() {
  return &corsa::cli::kApi;
}
