#pragma once

#include <span>
#include <string>

namespace corsa::cli {

/// Each function implements one plugin command (see plugin_api.h). They catch their own
/// exceptions: use guarded() to turn InputError and UsageError into messages and exit codes.
int plugin_selftest(std::span<const std::string> args);
/// `corsa map render` (cmd_map_render.cpp).
int plugin_map_render(std::span<const std::string> args);
/// `corsa convert ngii` (cmd_convert_ngii.cpp).
int plugin_convert(std::span<const std::string> args);
/// `corsa run ... --rig` (run_rig.cpp): the run with sensors and a dataset.
int plugin_run(std::span<const std::string> args);

/// Runs `body`, printing an InputError / UsageError as the executable would (exit 2) and any other
/// exception as an internal error (exit 3), so that no exception crosses the plugin boundary.
int guarded(const char* command, int (*body)(std::span<const std::string>),
            std::span<const std::string> args);

}  // namespace corsa::cli
