#include "actions.h"

#include <algorithm>
#include <iostream>

#include "args.h"
#include "exit_codes.h"

namespace corsa::cli {
namespace {

void print_help(const ActionMenu& menu, std::ostream& out) {
  out << "usage: corsa " << menu.command << ' ' << menu.synopsis << "\n\n"
      << menu.description << "\n\nactions:\n";
  for (const Action& action : menu.actions) {
    // Summaries start in one column (the eighth after the indent) under names up to six letters.
    const size_t width = std::max<size_t>(8, action.name.size() + 2);
    out << "  " << action.name << std::string(width - action.name.size(), ' ') << action.summary
        << '\n';
  }
  out << "\n  corsa " << menu.command << " ACTION --help   options of one action\n";
}

std::string action_names(const ActionMenu& menu) {
  std::string names;
  for (const Action& action : menu.actions) {
    names += (names.empty() ? "" : ", ") + std::string(action.name);
  }
  return names;
}

}  // namespace

int run_action(const ActionMenu& menu, std::span<const std::string> args) {
  if (args.empty()) {
    print_help(menu, std::cerr);
    return kExitBadInput;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    print_help(menu, std::cout);
    return kExitOk;
  }
  for (const Action& action : menu.actions) {
    if (args[0] == action.name) {
      return action.run(args.subspan(1));
    }
  }
  throw UsageError("unknown " + std::string(menu.command) + " action '" + args[0] + "' (" +
                   action_names(menu) + ")");
}

}  // namespace corsa::cli
