#include "exit_codes.h"

#include <filesystem>
#include <iostream>
#include <new>

#include "args.h"
#include "corsa/core/diagnostic.h"

namespace corsa::cli {

int guarded(std::string_view command, const std::function<int()>& body) {
  const std::string prefix = command.empty() ? "corsa" : "corsa " + std::string(command);
  try {
    return body();
  } catch (const UsageError& error) {
    std::cerr << prefix << ": error: " << error.what() << "\n(see '" << prefix << " --help')\n";
    return kExitBadInput;
  } catch (const InputError& error) {
    std::cerr << error.what() << '\n';
    return kExitBadInput;
  } catch (const std::filesystem::filesystem_error& error) {
    std::cerr << prefix << ": error: " << error.what() << '\n';
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "corsa: error: out of memory\n";
    return kExitInternal;
  } catch (const std::exception& error) {
    std::cerr << "corsa: internal error: " << error.what() << "\n(this is a bug in Corsa)\n";
    return kExitInternal;
  }
}

int guarded(std::string_view command, int (*body)(std::span<const std::string>),
            std::span<const std::string> args) {
  return guarded(command, [body, args] { return body(args); });
}

}  // namespace corsa::cli
