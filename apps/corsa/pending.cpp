#include "pending.h"

#include <iostream>

#include "commands.h"

namespace corsa::cli {

int pending_command(const ArgParser& parser, std::span<const std::string> args,
                    const std::string& name) {
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  std::cerr << "corsa " << name
            << ": error: not available in this build yet (see the status table in README.md)\n";
  return kExitBadInput;
}

}  // namespace corsa::cli
