#pragma once

// The boundary between the light `corsa` executable and libcorsa_plugin.so.
//
// Why: Debian's OpenCV (imgcodecs pulls GDAL, videoio pulls FFmpeg and GStreamer) and PROJ (curl,
// TLS, sqlite) cost 100-300 ms just to load, measured on this 2-core machine, while a whole
// scenario run should take ~10 ms. So `corsa` links only core, xodr, xosc and engine; everything
// that needs OpenCV, PROJ, Embree or assimp (NGII conversion, map rendering, sensors) is built
// into the plugin, which `corsa` loads with dlopen only for the commands that need it.
//
// GeoPositions need PROJ too, but nothing else of the plugin: loading libproj alone costs about
// 10 ms of CPU where the whole plugin costs about 150 ms (medians of a program that only dlopens
// them, on this machine). So PROJ's transform for the engine has a module of its own,
// libcorsa_proj.so (proj_plugin/), which `corsa run`, `sweep` and `test` load on the first
// GeoPosition of a run; a scenario without one never loads it.
//
// Both sides are built from the same tree with the same compiler and flags, so C++ types may
// cross the boundary; the ABI version guards against a stale plugin.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "corsa/engine/simulation.h"

namespace corsa::cli {

inline constexpr uint32_t kPluginAbiVersion = 1;

/// A subcommand implemented in the plugin. Returns an ExitCode; catches its own exceptions
/// (guarded(), exit_codes.h) so that nothing is thrown across the boundary.
using PluginCommand = int (*)(std::span<const std::string> args);

struct PluginCommandEntry {
  std::string_view name;  ///< e.g. "convert", "map render"
  PluginCommand run;
};

struct PluginApi {
  uint32_t abi_version = 0;
  std::span<const PluginCommandEntry> commands;
};

/// The plugin's entry point (exported with C linkage from libcorsa_plugin.so).
using PluginEntry = const PluginApi* (*)();
inline constexpr const char* kPluginEntryName = "corsa_plugin_api";
inline constexpr const char* kPluginFileName = "libcorsa_plugin.so";

/// Executable side: loads the plugin (next to the executable, or $CORSA_PLUGIN) on first use and
/// runs its command `name`. A missing or stale plugin is reported (exit 2), never a crash.
int run_plugin_command(std::string_view name, std::span<const std::string> args);

/// libcorsa_proj.so's one function: PROJ's transform from WGS84 into a map's geoReference
/// (corsa::geo::geographic_to_projected). On failure it returns an empty function and says why
/// in `error`: nothing is thrown across the boundary, and the transform it returns throws
/// nothing either.
using GeographicToMapMaker = engine::GeographicToMap (*)(const std::string& geo_reference,
                                                         std::string& error);

struct ProjPluginApi {
  uint32_t abi_version = 0;
  GeographicToMapMaker geographic_to_map = nullptr;
};

using ProjPluginEntry = const ProjPluginApi* (*)();
inline constexpr const char* kProjPluginEntryName = "corsa_proj_plugin_api";
inline constexpr const char* kProjPluginFileName = "libcorsa_proj.so";

/// Executable side: the GeoPositions' transform for SimulationOptions::geo_projection. Loads
/// libcorsa_proj.so (next to the executable, or $CORSA_PROJ_PLUGIN) on its first call, once per
/// process and safely from any thread; throws corsa::InputError saying why when it cannot.
engine::GeoProjectionFactory proj_plugin_geo_projection();

}  // namespace corsa::cli
