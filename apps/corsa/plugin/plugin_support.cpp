#include <exception>
#include <iostream>
#include <new>

#include "args.h"
#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/version.h"
#include "plugin_api.h"
#include "plugin_commands.h"

namespace corsa::cli {

int guarded(const char* command, int (*body)(std::span<const std::string>),
            std::span<const std::string> args) {
  try {
    return body(args);
  } catch (const UsageError& error) {
    std::cerr << "corsa " << command << ": error: " << error.what() << "\n(see 'corsa " << command
              << " --help')\n";
    return kExitBadInput;
  } catch (const InputError& error) {
    std::cerr << error.diagnostic().format() << '\n';
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "corsa: error: out of memory\n";
    return kExitInternal;
  } catch (const std::exception& error) {
    std::cerr << "corsa: internal error: " << error.what() << "\n(this is a bug in Corsa)\n";
    return kExitInternal;
  }
}

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
