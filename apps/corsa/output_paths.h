#pragma once

// Output paths named on the command line, read the one way every `corsa` command treats them:
// checked when the arguments are read, before any work (not after an hour of simulation).
// Missing folders on the way are made when the output is written (like `mkdir -p`); an output
// file that is a folder, or any output whose path runs through a regular file, is refused with an
// InputError naming it (exit 2). Temporaries a killed run of Corsa left there (in the output
// file's folder, or anywhere in an output folder) are removed. See corsa/core/atomic_file.h.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "args.h"

namespace corsa::cli {

/// Checks a file name before the filesystem is asked, e.g. its extension; throws UsageError.
using OutputNameCheck = std::function<void(const std::filesystem::path&)>;

/// The output file given with `option`, checked; nullopt when the option is absent.
std::optional<std::filesystem::path> output_file(const ParsedArgs& parsed,
                                                 const std::string& option);

/// The output file given with `option`, which must be there: UsageError "missing OPTION
/// `missing`" (e.g. `missing` = "FILE.png (the picture to write)") when it is absent or empty.
/// `check_name`, when given, sees the name before the filesystem check.
std::filesystem::path required_output_file(const ParsedArgs& parsed, const std::string& option,
                                           const std::string& missing,
                                           const OutputNameCheck& check_name = {});

/// The output folder given with `option`, checked; `fallback` (checked too) when absent.
std::filesystem::path output_folder(const ParsedArgs& parsed, const std::string& option,
                                    const std::filesystem::path& fallback);
/// The output folder given with `option`, checked; nullopt when the option is absent.
std::optional<std::filesystem::path> output_folder(const ParsedArgs& parsed,
                                                   const std::string& option);
/// The output folder given with `option`, which must be there (as required_output_file).
std::filesystem::path required_output_folder(const ParsedArgs& parsed, const std::string& option,
                                             const std::string& missing);

}  // namespace corsa::cli
