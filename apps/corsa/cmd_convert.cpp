// `corsa convert ngii DIR -o OUT.xodr`: the NGII import needs PROJ and shapelib, which the corsa
// executable does not load (see plugin_api.h); the command runs in libcorsa_plugin.so
// (plugin/cmd_convert_ngii.cpp).

#include "commands.h"
#include "plugin_api.h"

namespace corsa::cli {

int command_convert(std::span<const std::string> args) {
  return run_plugin_command("convert", args);
}

}  // namespace corsa::cli
