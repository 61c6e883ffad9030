#include <iostream>

#include "args.h"
#include "commands.h"
#include "corsa/core/version.h"
#include "plugin_api.h"
#include "plugin_commands.h"

namespace corsa::cli {

namespace {

int selftest_body(std::span<const std::string> args) {
  if (!args.empty()) {
    throw UsageError("unexpected argument '" + args.front() + "'");
  }
  std::cout << "corsa plugin " << version() << " abi " << kPluginAbiVersion << '\n';
  return kExitOk;
}

}  // namespace

int plugin_selftest(std::span<const std::string> args) {
  return guarded("plugin selftest", selftest_body, args);
}

}  // namespace corsa::cli
