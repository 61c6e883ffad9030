// `corsa`: the command line. Thin by design: it parses arguments, wires the libraries together and
// prints; every behaviour lives in the libraries.

#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "corsa/core/version.h"
#include "plugin_api.h"

namespace corsa::cli {
namespace {

const Command kCommands[] = {
    {"run", "run one scenario: trajectories, summary, optional sensor dataset", command_run},
    {"validate", "check .xosc / .xodr files and print located errors", command_validate},
    {"map", "inspect OpenDRIVE maps: info, query, render, mesh, holes", command_map},
    {"convert", "convert map data to OpenDRIVE (NGII HD road layers)", command_convert},
    {"sweep", "run parameter variants in parallel or sharded over a cluster", command_sweep},
    {"test", "run a regression suite with goldens and a JUnit report", command_test},
    {"record", "binary trajectories: export to CSV, info", command_record},
};

void print_main_help(std::ostream& out) {
  out << "usage: corsa <command> [options]\n\n"
         "Corsa runs OpenSCENARIO scenarios over OpenDRIVE maps, headless and deterministic, and\n"
         "collects sensor data on a schedule the scenario's triggers drive.\n\ncommands:\n";
  for (const auto& command : kCommands) {
    out << "  " << std::left << std::setw(10) << command.name << ' ' << command.summary << '\n';
  }
  out << "\n  corsa <command> --help   options of one command\n"
         "  corsa --version          version (--version --plugin: also check the plugin)\n\n"
         "exit codes: 0 ok, 1 scenario or test failed, 2 bad input or usage, 3 internal error\n";
}

int dispatch(const std::vector<std::string>& argv) {
  if (argv.empty()) {
    print_main_help(std::cerr);
    return kExitBadInput;
  }
  const std::string& first = argv[0];
  if (first == "--help" || first == "-h" || first == "help") {
    if (first == "help" && argv.size() > 1) {
      return dispatch({argv[1], "--help"});
    }
    print_main_help(std::cout);
    return kExitOk;
  }
  if (first == "--version" || first == "version") {
    std::cout << "corsa " << version() << '\n';
    if (argv.size() > 1 && argv[1] == "--plugin") {
      // Loads libcorsa_plugin.so and reports its version: checks that the heavy half is there.
      return run_plugin_command("plugin selftest", {});
    }
    return kExitOk;
  }
  for (const auto& command : kCommands) {
    if (command.name == first) {
      const std::vector<std::string> rest(argv.begin() + 1, argv.end());
      return guarded(first, command.run, rest);
    }
  }
  std::cerr << "corsa: error: unknown command '" << first << "' (see 'corsa --help')\n";
  return kExitBadInput;
}

}  // namespace

std::span<const Command> commands() { return kCommands; }

}  // namespace corsa::cli

int main(int argc, char** argv) {
  using namespace corsa::cli;
  std::ios::sync_with_stdio(false);
  const std::vector<std::string> args(argv + 1, argv + argc);
  return guarded("", [&args] { return dispatch(args); });
}
