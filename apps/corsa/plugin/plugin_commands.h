#pragma once

#include <span>
#include <string>

namespace corsa::cli {

/// Each function implements one plugin command (see plugin_api.h). They catch their own
/// exceptions through guarded() (exit_codes.h), as the executable's commands do.
int plugin_selftest(std::span<const std::string> args);
/// `corsa map render` (cmd_map_render.cpp).
int plugin_map_render(std::span<const std::string> args);
/// `corsa convert ngii` (cmd_convert_ngii.cpp).
int plugin_convert(std::span<const std::string> args);
/// `corsa run ... --rig` (run_rig.cpp): the run with sensors and a dataset.
int plugin_run(std::span<const std::string> args);

}  // namespace corsa::cli
