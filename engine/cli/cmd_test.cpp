#include "commands.h"
#include "pending.h"

namespace corsa::cli {

int command_test(std::span<const std::string> args) {
  ArgParser parser("test SUITE [options]",
                   "Runs a regression suite: expectations, goldens, JUnit report.");
  parser.positional("SUITE", "suite folder or manifest");
  return pending_command(parser, args, "test");
}

}  // namespace corsa::cli
