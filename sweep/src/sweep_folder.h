#pragma once

// Internal: the files of a sweep output folder (see sweep.h) and how they are read back.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/json.h"

namespace corsa::sweep::detail {

inline constexpr const char* kDescriptionFile = "sweep.json";
inline constexpr const char* kShardFile = "shard.json";
inline constexpr const char* kSummaryFile = "summary.csv";
inline constexpr const char* kVariantsFolder = "variants";
inline constexpr const char* kResultFile = "result.csv";
inline constexpr const char* kTrajectoryFile = "trajectory.csv";
inline constexpr const char* kRunSummaryFile = "summary.json";

/// The plan hash a sweep.json states (its member "plan"); empty when it has none.
std::string plan_of(const Json& description);

/// The variant count a sweep.json states (its member "variants"); nothing when it has none.
std::optional<size_t> variant_count_of(const Json& description);

/// A CSV table: header and rows.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// Reads a CSV table; nothing when the file is missing, malformed or has rows of another width
/// than the header. Throws InputError for a path that is not a regular file of bounded size (a
/// FIFO, a device: see read_file).
std::optional<Table> read_table(const std::filesystem::path& file);

/// The variant index in a row's first field; nothing when it is not a whole number.
std::optional<size_t> row_index(const std::vector<std::string>& row);

}  // namespace corsa::sweep::detail
