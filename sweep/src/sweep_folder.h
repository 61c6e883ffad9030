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

/// The entries of `out` that replacing the earlier sweep or merge there removes (files first,
/// then folders innermost first): exactly what a sweep writes and sweep.json accounts for, which
/// is sweep.json, shard.json, summary.csv, the lock, variants/<i>/ for i below sweep.json's
/// variant count with their trajectory.csv, summary.json and result.csv, and Corsa's
/// temporaries. A folder without a sweep.json of Corsa's (JSON with a plan and a variant count),
/// or with anything else in it (a file of the user's, a symbolic link, variants/<i> beyond the
/// count), is an InputError before anything is removed: `--force` never empties a folder whole.
std::vector<std::filesystem::path> replaceable_entries(const std::filesystem::path& out);

/// `--resume`: throws InputError unless `out` holds the sweep `description` describes (its
/// sweep.json has the same plan) and the same shard (`shard`, null for a whole sweep, equals
/// shard.json, absent for a whole sweep).
void check_resumable(const std::filesystem::path& out, const Json& description, const Json& shard);

/// A variant's row from an earlier run in its folder's result.csv, if it finished: a table of
/// exactly `header` with one row, for variant `index`.
std::optional<std::vector<std::string>> finished_row(const std::filesystem::path& folder,
                                                     size_t index,
                                                     const std::vector<std::string>& header);

}  // namespace corsa::sweep::detail
