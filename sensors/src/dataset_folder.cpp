// The folder of a dataset before it is written: empty, or a previous dataset to replace
// (dataset_folder.h). `--force` once removed any folder that merely held a file named run.json,
// with everything else in it; now it removes the previous dataset's own files, and refuses a
// folder that holds anything more.

#include "dataset_folder.h"

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/output_lock.h"
#include "corsa/core/strings.h"

namespace corsa::sensors::detail {
namespace {

namespace fs = std::filesystem;

// The frame index's header; datasets since the overlap flag add a seventh column.
constexpr std::string_view kIndexHeader = "capture,tick,time,sensor,frame,file";
constexpr std::string_view kIndexHeaderWithOverlap = "capture,tick,time,sensor,frame,file,overlap";
constexpr size_t kIndexFileColumn = 5;

[[noreturn]] void fail(const fs::path& where, int line, const std::string& message) {
  throw InputError(make_error(where.string(), line, message));
}

/// What the previous dataset's run.json and frames.csv name.
struct PreviousDataset {
  std::set<std::string> sensors;  ///< folder names
  std::set<fs::path> indexed;     ///< relative paths
};

bool is_sensor_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

std::set<std::string> sensors_of(const fs::path& run_json) {
  const nlohmann::json run = nlohmann::json::parse(read_file(run_json), nullptr, false);
  const auto not_ours = [&] {
    fail(run_json, 0,
         "is not the run.json of a Corsa dataset; --force replaces only a previous dataset");
  };
  if (!run.is_object() || !run.contains("corsa_version") || !run.contains("sensors") ||
      !run["sensors"].is_array()) {
    not_ours();
  }
  std::set<std::string> sensors;
  for (const auto& sensor : run["sensors"]) {
    if (!sensor.is_object() || !sensor.contains("name") || !sensor["name"].is_string() ||
        !is_sensor_name(sensor["name"].get<std::string>())) {
      not_ours();
    }
    sensors.insert(sensor["name"].get<std::string>());
  }
  return sensors;
}

/// A path frames.csv names: relative and inside the dataset.
bool is_inside(const fs::path& path) {
  if (path.empty() || path.has_root_path()) return false;
  return std::none_of(path.begin(), path.end(), [](const fs::path& part) {
    return part == ".." || part == "." || part.empty();
  });
}

std::set<fs::path> indexed_files(const fs::path& index) {
  std::set<fs::path> files;
  std::error_code error;
  if (!fs::exists(index, error)) return files;
  const std::string text = read_file(index);
  int line = 0;
  for (const std::string_view row : split(text, '\n')) {
    ++line;
    if (line == 1) {
      if (trim(row) != kIndexHeader && trim(row) != kIndexHeaderWithOverlap) {
        fail(index, 1, "is not the index of a Corsa dataset");
      }
      continue;
    }
    if (trim(row).empty()) continue;
    const std::vector<std::string_view> fields = split(trim(row), ',');
    if (fields.size() <= kIndexFileColumn) {
      fail(index, line, "is not a row of a Corsa dataset's index");
    }
    const fs::path file(std::string(trim(fields[kIndexFileColumn])));
    if (!is_inside(file)) {
      fail(index, line, "names '" + clip(file.string()) + "', which is not inside the dataset");
    }
    files.insert(file.lexically_normal());
  }
  return files;
}

bool is_frame_name(const std::string& name) {
  return name.size() > 6 &&
         std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
}

/// Whether `file` (relative) is one of the files the previous dataset made.
bool is_own(const fs::path& file, const PreviousDataset& previous) {
  const std::vector<std::string> parts(file.begin(), file.end());
  const std::string& name = parts.back();
  // AtomicFile's temporaries (a killed run leaves them; no live one: the caller holds the lock).
  if (previous.indexed.contains(file) || is_temporary_name(name)) return true;
  if (parts.size() == 1) {
    return name == "run.json" || name == "frames.csv" || name == "classes.json" ||
           name == OutputLock::kFileName;
  }
  const std::string& folder = parts.front();
  if (parts.size() == 2) {
    if (previous.sensors.contains(folder)) return name == "calibration.json" || is_frame_name(name);
    if (folder == "poses") return is_frame_name(name) && file.extension() == ".json";
    if (folder == "preview") {
      return name == "contact_sheet.png" || name.starts_with("camera_birds_eye.") ||
             name.starts_with(".camera_birds_eye.tmp.");
    }
    return false;
  }
  // The KITTI export: training/<folder>/NNNNNN.* and ImageSets/{train,val,trainval}.txt.
  static const std::set<std::string> kKittiFolders{"image_2", "label_2", "calib", "velodyne"};
  static const std::set<std::string> kKittiSets{"train.txt", "val.txt", "trainval.txt"};
  if (folder != "kitti") return false;
  if (parts.size() == 3) return parts[1] == "ImageSets" && kKittiSets.contains(name);
  return parts.size() == 4 && parts[1] == "training" && kKittiFolders.contains(parts[2]) &&
         is_frame_name(name);
}

}  // namespace

void prepare_dataset_folder(const fs::path& dir, bool replace) {
  std::vector<fs::path> files;  // relative; anything that is not a folder (links not followed)
  std::vector<fs::path> folders;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const fs::path relative = fs::relative(entry.path(), dir);
    if (entry.is_directory() && !entry.is_symlink()) {
      folders.push_back(entry.path());
    } else if (relative != OutputLock::kFileName) {
      files.push_back(relative);
    }
  }
  if (files.empty() && folders.empty()) return;
  if (!replace) {
    fail(dir, 0, "the dataset folder is not empty (use --force to replace a previous dataset)");
  }
  std::error_code error;
  if (!fs::is_regular_file(dir / "run.json", error)) {
    fail(dir, 0,
         "--force replaces only a previous dataset (a folder with a run.json); this folder has "
         "none");
  }
  const PreviousDataset previous{sensors_of(dir / "run.json"), indexed_files(dir / "frames.csv")};
  std::vector<std::string> foreign;
  for (const fs::path& file : files) {
    if (!is_own(file, previous)) foreign.push_back(file.string());
  }
  if (!foreign.empty()) {
    std::sort(foreign.begin(), foreign.end());
    std::string examples;
    for (size_t i = 0; i < foreign.size() && i < 3; ++i) {
      examples += (i ? ", " : "") + clip(foreign[i]);
    }
    fail(dir, 0,
         "--force replaces only a previous dataset, and this folder also holds " +
             std::to_string(foreign.size()) + " file" + (foreign.size() == 1 ? "" : "s") +
             " that its run.json and frames.csv do not name (" + examples +
             (foreign.size() > 3 ? ", ..." : "") +
             "); nothing was removed: move them away or choose another folder");
  }
  for (const fs::path& file : files) {
    if (!fs::remove(dir / file, error) && error) {
      fail(dir / file, 0, "cannot remove: " + error.message());
    }
  }
  // Innermost first; a folder is removed only when empty.
  std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
    return std::distance(a.begin(), a.end()) > std::distance(b.begin(), b.end());
  });
  for (const fs::path& folder : folders) fs::remove(folder, error);
}

}  // namespace corsa::sensors::detail
