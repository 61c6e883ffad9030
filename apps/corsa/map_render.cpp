// `corsa map render`: the picture needs OpenCV, which the corsa executable does not load (see
// plugin_api.h); the command runs in libcorsa_plugin.so (plugin/cmd_map_render.cpp).

#include "map_actions.h"
#include "plugin_api.h"

namespace corsa::cli {

int map_render(std::span<const std::string> args) { return run_plugin_command("map render", args); }

}  // namespace corsa::cli
