#include <dlfcn.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "commands.h"
#include "plugin_api.h"

namespace corsa::cli {
namespace {

std::filesystem::path plugin_path() {
  if (const char* override_path = std::getenv("CORSA_PLUGIN")) {
    return override_path;
  }
  std::error_code error;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path(kPluginFileName) : exe.parent_path() / kPluginFileName;
}

const PluginApi* load_api() {
  const std::filesystem::path path = plugin_path();
  // The handle stays open for the life of the process: the plugin's code runs until exit.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    std::cerr << "corsa: error: cannot load " << path.string() << " (" << ::dlerror()
              << "); it is built next to the corsa executable\n";
    return nullptr;
  }
  auto entry = reinterpret_cast<PluginEntry>(::dlsym(handle, kPluginEntryName));
  const PluginApi* api = entry != nullptr ? entry() : nullptr;
  if (api == nullptr || api->abi_version != kPluginAbiVersion) {
    std::cerr << "corsa: error: " << path.string()
              << " does not match this corsa executable (rebuild both)\n";
    return nullptr;
  }
  return api;
}

}  // namespace

int run_plugin_command(std::string_view name, std::span<const std::string> args) {
  const PluginApi* api = load_api();
  if (api == nullptr) {
    return kExitBadInput;
  }
  for (const auto& command : api->commands) {
    if (command.name == name) {
      return command.run(args);
    }
  }
  std::cerr << "corsa: error: '" << name << "' is not available in this build's plugin\n";
  return kExitBadInput;
}

}  // namespace corsa::cli
