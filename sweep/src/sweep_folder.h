#pragma once

// Internal: the files of a sweep output folder (see sweep.h) and how they are read back.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace corsa::sweep::detail {

inline constexpr const char* kDescriptionFile = "sweep.json";
inline constexpr const char* kShardFile = "shard.json";
inline constexpr const char* kSummaryFile = "summary.csv";
inline constexpr const char* kVariantsFolder = "variants";
inline constexpr const char* kResultFile = "result.csv";
inline constexpr const char* kTrajectoryFile = "trajectory.csv";
inline constexpr const char* kRunSummaryFile = "summary.json";

/// The raw text of a top-level member `"key": value` of a JSON object Corsa wrote (one member per
/// line); nothing when absent. Strings keep their quotes.
std::optional<std::string> json_member(std::string_view json, std::string_view key);

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
