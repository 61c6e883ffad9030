// libFuzzer target: a dataset folder's index as `corsa run --rig --force` reads it back before
// replacing a previous dataset: run.json, frames.csv and the list of files the folder holds (one
// relative path a line; a line "@name" plants a symbolic link to a folder outside), cut apart at
// the part separator (fuzz_parts.h). Bad input must end in corsa::InputError with nothing
// removed; a replacement must remove every file and never anything outside the folder.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "dataset_folder.h"
#include "fuzz_parts.h"

namespace {

namespace fs = std::filesystem;

// A relative path the fuzzer may create: no root, no "." or "..", at most 4 levels.
bool creatable(const fs::path& path) {
  if (path.empty() || path.has_root_path()) return false;
  size_t depth = 0;
  for (const fs::path& part : path) {
    if (part.empty() || part == "." || part == ".." || ++depth > 4) return false;
  }
  return true;
}

/// Creates the listed files (at most 32) below `dir`; returns those made.
std::vector<fs::path> plant(const fs::path& dir, const fs::path& outside, std::string_view list) {
  std::vector<fs::path> made;
  for (std::string_view line : corsa::split(list, '\n')) {
    if (made.size() == 32) break;
    const bool link = line.starts_with('@');
    const fs::path relative(std::string(line.substr(link ? 1 : 0)));
    if (!creatable(relative)) continue;
    std::error_code error;
    fs::create_directories((dir / relative).parent_path(), error);
    if (error || fs::exists(fs::symlink_status(dir / relative, error))) continue;
    if (link) {
      fs::create_directory_symlink(outside, dir / relative, error);
    } else {
      corsa::fuzz::write_bytes(dir / relative, "frame");
    }
    if (!error && fs::exists(fs::symlink_status(dir / relative, error))) made.push_back(relative);
  }
  return made;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const fs::path kScratch = corsa::fuzz::scratch_folder("dataset_index_fuzz");
  const fs::path dir = kScratch / "dataset";
  const fs::path outside = kScratch / "outside";
  std::error_code error;
  fs::remove_all(dir, error);
  fs::create_directories(dir);
  fs::create_directories(outside);
  corsa::fuzz::write_bytes(outside / "keep.txt", "not the dataset's");
  const auto parts = corsa::fuzz::split_parts(data, size, 3);
  std::vector<fs::path> made = plant(dir, outside, parts[2]);
  if (!parts[0].empty() && !fs::exists(fs::symlink_status(dir / "run.json", error))) {
    corsa::fuzz::write_bytes(dir / "run.json", parts[0]);
    made.push_back("run.json");
  }
  if (!parts[1].empty() && !fs::exists(fs::symlink_status(dir / "frames.csv", error))) {
    corsa::fuzz::write_bytes(dir / "frames.csv", parts[1]);
    made.push_back("frames.csv");
  }
  bool replaced = false;
  try {
    corsa::sensors::detail::prepare_dataset_folder(dir, true);
    replaced = true;
  } catch (const corsa::InputError&) {
    // Refused: nothing may have been removed.
    for (const fs::path& file : made) {
      if (!fs::exists(fs::symlink_status(dir / file, error))) std::abort();
    }
  }
  if (replaced) {
    // Replaced: no file (nor link) may be left.
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (!entry.is_directory() || entry.is_symlink()) std::abort();
    }
  }
  if (!fs::exists(outside / "keep.txt", error)) std::abort();
  return 0;
}
