#include <dlfcn.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "plugin_api.h"

namespace corsa::cli {
namespace {

// `file` next to the executable, or the path in the environment variable `override_variable`.
std::filesystem::path module_path(const char* file, const char* override_variable) {
  if (const char* override_path = std::getenv(override_variable)) {
    return override_path;
  }
  std::error_code error;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path(file) : exe.parent_path() / file;
}

std::string stale(const char* file, const char* override_variable) {
  return module_path(file, override_variable).string() +
         " does not match this corsa executable (rebuild both)";
}

// A loaded module's entry point, or why there is none.
struct Loaded {
  void* entry = nullptr;
  std::string error;
};

Loaded load_module(const char* file, const char* override_variable, const char* entry_name) {
  const std::filesystem::path path = module_path(file, override_variable);
  // The handle stays open for the life of the process: the module's code runs until exit.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    return {nullptr, "cannot load " + path.string() + " (" + ::dlerror() +
                         "); it is built next to the corsa executable"};
  }
  void* entry = ::dlsym(handle, entry_name);
  if (entry == nullptr) {
    return {nullptr, stale(file, override_variable)};
  }
  return {entry, {}};
}

const PluginApi* load_api() {
  const Loaded loaded = load_module(kPluginFileName, "CORSA_PLUGIN", kPluginEntryName);
  if (loaded.entry == nullptr) {
    std::cerr << "corsa: error: " << loaded.error << "\n";
    return nullptr;
  }
  const PluginApi* api = reinterpret_cast<PluginEntry>(loaded.entry)();
  if (api == nullptr || api->abi_version != kPluginAbiVersion) {
    std::cerr << "corsa: error: " << stale(kPluginFileName, "CORSA_PLUGIN") << "\n";
    return nullptr;
  }
  return api;
}

// libcorsa_proj.so, loaded once per process (a function-local static: safe from sweep threads).
struct ProjPlugin {
  const ProjPluginApi* api = nullptr;
  std::string error;
};

const ProjPlugin& proj_plugin() {
  static const ProjPlugin plugin = [] {
    const Loaded loaded =
        load_module(kProjPluginFileName, "CORSA_PROJ_PLUGIN", kProjPluginEntryName);
    if (loaded.entry == nullptr) {
      return ProjPlugin{nullptr, loaded.error};
    }
    const ProjPluginApi* api = reinterpret_cast<ProjPluginEntry>(loaded.entry)();
    if (api == nullptr || api->abi_version != kPluginAbiVersion) {
      return ProjPlugin{nullptr, stale(kProjPluginFileName, "CORSA_PROJ_PLUGIN")};
    }
    return ProjPlugin{api, {}};
  }();
  return plugin;
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

engine::GeoProjectionFactory proj_plugin_geo_projection() {
  return [](const std::string& geo_reference) {
    const ProjPlugin& proj = proj_plugin();
    if (proj.api == nullptr) {
      throw InputError(make_error("", 0, "GeoPosition needs PROJ, but " + proj.error));
    }
    std::string error;
    engine::GeographicToMap transform = proj.api->geographic_to_map(geo_reference, error);
    if (!transform) {
      throw InputError(make_error("", 0, error));
    }
    return transform;
  };
}

}  // namespace corsa::cli
