// libcorsa_plugin.so: the commands that need OpenCV, PROJ, Embree or assimp (see plugin_api.h).
// Each command registers here; the entry point hands the table to the corsa executable.

#include <array>

#include "plugin_api.h"
#include "plugin_commands.h"

namespace corsa::cli {
namespace {

const auto kCommands = std::to_array<PluginCommandEntry>({
    {"plugin selftest", plugin_selftest},
    {"map render", plugin_map_render},
    {"convert", plugin_convert},
    {"run", plugin_run},
});

const PluginApi kApi{kPluginAbiVersion, kCommands};

}  // namespace
}  // namespace corsa::cli

extern "C" __attribute__((visibility("default"))) const corsa::cli::PluginApi* corsa_plugin_api() {
  return &corsa::cli::kApi;
}
