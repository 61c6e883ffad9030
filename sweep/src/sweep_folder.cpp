#include "sweep_folder.h"

#include <algorithm>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/input_file.h"
#include "corsa/core/output_lock.h"
#include "corsa/core/strings.h"
#include "corsa/sweep/csv.h"

namespace corsa::sweep::detail {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& where, const std::string& message) {
  throw InputError(make_error(where.string(), 0, message));
}

// Whether `relative` (below a sweep folder; `folder` when it is a real folder, not a link) is one
// of the entries a sweep or a merge writes: sweep.json, shard.json, summary.csv, the lock,
// variants/<i>/ (i below `variants`) and their trajectory.csv, summary.json and result.csv, and
// temporaries.
bool is_sweep_entry(const fs::path& relative, bool folder, size_t variants) {
  const std::vector<std::string> parts(relative.begin(), relative.end());
  const std::string& name = parts.back();
  if (is_temporary_name(name)) return !folder;
  switch (parts.size()) {
    case 1:
      return folder ? name == kVariantsFolder
                    : name == kDescriptionFile || name == kShardFile || name == kSummaryFile ||
                          name == OutputLock::kFileName;
    case 2: {
      const auto index = row_index({name});
      return folder && parts[0] == kVariantsFolder && index && *index < variants;
    }
    case 3:
      return !folder && parts[0] == kVariantsFolder &&
             (name == kTrajectoryFile || name == kRunSummaryFile || name == kResultFile);
    default:
      return false;
  }
}

// The variant count of `description` when it is a sweep.json of Corsa's: JSON with the plan hash
// and the count.
std::optional<size_t> own_variant_count(const fs::path& description) {
  const std::string text = read_file(description);
  try {
    const Json described = parse_json(text, description.string());
    if (plan_of(described).empty()) return std::nullopt;
    return variant_count_of(described);
  } catch (const InputError&) {
    return std::nullopt;  // not JSON: not Corsa's
  }
}

}  // namespace

std::vector<fs::path> replaceable_entries(const fs::path& out) {
  std::error_code error;
  const fs::path description = out / kDescriptionFile;
  const auto variants = fs::is_regular_file(fs::symlink_status(description, error))
                            ? own_variant_count(description)
                            : std::nullopt;
  if (!variants) {
    fail(out,
         "--force replaces only an earlier sweep or merge (a folder with Corsa's sweep.json); "
         "this folder has none, and nothing was removed");
  }
  std::vector<fs::path> files;
  std::vector<fs::path> folders;
  std::vector<std::string> foreign;
  for (fs::recursive_directory_iterator it(out, error), end; !error && it != end;
       it.increment(error)) {
    std::error_code ignored;
    const bool folder = fs::is_directory(it->symlink_status(ignored));
    const fs::path relative = it->path().lexically_relative(out);
    if (!is_sweep_entry(relative, folder, *variants)) {
      foreign.push_back(relative.string());
      if (folder) it.disable_recursion_pending();
    }
    (folder ? folders : files).push_back(it->path());
  }
  if (error) fail(out, "cannot read the folder (" + error.message() + ")");
  if (!foreign.empty()) {
    std::sort(foreign.begin(), foreign.end());
    std::string examples;
    for (size_t i = 0; i < foreign.size() && i < 3; ++i) {
      examples += (i ? ", " : "") + clip(foreign[i]);
    }
    fail(out, "--force replaces only an earlier sweep or merge, and this folder also holds " +
                  std::to_string(foreign.size()) + " entr" + (foreign.size() == 1 ? "y" : "ies") +
                  " a sweep does not write (" + examples + (foreign.size() > 3 ? ", ..." : "") +
                  "); nothing was removed: move them away or choose another folder");
  }
  std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
    return std::distance(a.begin(), a.end()) > std::distance(b.begin(), b.end());
  });
  files.insert(files.end(), folders.begin(), folders.end());
  return files;
}

std::string plan_of(const Json& description) {
  const auto plan = description.find("plan");
  return plan != description.end() && plan->is_string() ? plan->get<std::string>() : "";
}

std::optional<size_t> variant_count_of(const Json& description) {
  const auto count = description.find("variants");
  if (count == description.end() || !count->is_number_unsigned()) return std::nullopt;
  return count->get<size_t>();
}

std::optional<Table> read_table(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return std::nullopt;
  // Anything but a regular file of bounded size is an error (a FIFO would block).
  const std::string text = read_file(file);
  std::vector<std::vector<std::string>> rows;
  if (!parse_csv(text, rows) || rows.empty()) return std::nullopt;
  Table table;
  table.header = std::move(rows.front());
  rows.erase(rows.begin());
  for (const auto& row : rows) {
    if (row.size() != table.header.size()) return std::nullopt;
  }
  table.rows = std::move(rows);
  return table;
}

std::optional<size_t> row_index(const std::vector<std::string>& row) {
  if (row.empty()) return std::nullopt;
  const auto value = parse_int(row.front());
  if (!value || *value < 0) return std::nullopt;
  return static_cast<size_t>(*value);
}

void check_resumable(const fs::path& out, const Json& description, const Json& shard) {
  if (plan_of(read_json_file(out / kDescriptionFile)) != plan_of(description)) {
    fail(out,
         "--resume: this folder holds a different sweep (other scenario, parameters, variants or "
         "options); its sweep.json does not match");
  }
  std::error_code error;
  const fs::path shard_file = out / kShardFile;
  const Json existing = fs::exists(shard_file, error) ? read_json_file(shard_file) : Json();
  if (existing != shard) fail(out, "--resume: this folder holds another shard of the sweep");
}

std::optional<std::vector<std::string>> finished_row(const fs::path& folder, size_t index,
                                                     const std::vector<std::string>& header) {
  const auto table = read_table(folder / kResultFile);
  if (!table || table->header != header || table->rows.size() != 1 ||
      row_index(table->rows.front()) != index) {
    return std::nullopt;
  }
  return table->rows.front();
}

}  // namespace corsa::sweep::detail
