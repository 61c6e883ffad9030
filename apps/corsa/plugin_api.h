#pragma once

// The boundary between the light `corsa` executable and libcorsa_plugin.so.
//
// Why: Debian's OpenCV (imgcodecs pulls GDAL, videoio pulls FFmpeg and GStreamer) and PROJ (curl,
// TLS, sqlite) cost 100-300 ms just to load, measured on this 2-core machine, while a whole
// scenario run should take ~10 ms. So `corsa` links only core, xodr, xosc and engine; everything
// that needs OpenCV, PROJ, Embree or assimp (NGII conversion, map rendering, sensors) is built
// into the plugin, which `corsa` loads with dlopen only for the commands that need it.
//
// Both sides are built from the same tree with the same compiler and flags, so C++ types may
// cross the boundary; the ABI version guards against a stale plugin.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

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

}  // namespace corsa::cli
