#pragma once

#include <span>
#include <string>

#include "args.h"

namespace corsa::cli {

/// For a subcommand whose engine is not in this build yet: prints its --help, and otherwise says
/// plainly that it is not available (exit 2), instead of pretending to work.
int pending_command(const ArgParser& parser, std::span<const std::string> args,
                    const std::string& name);

}  // namespace corsa::cli
