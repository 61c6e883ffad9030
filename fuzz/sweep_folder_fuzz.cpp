// libFuzzer target: the files of a sweep output folder as `corsa sweep merge` and
// `corsa sweep --resume` / `--force` read them back: sweep.json, shard.json, summary.csv and
// variants/0/result.csv, cut apart at the part separator (fuzz_parts.h; an empty part is a
// missing file). The folder is merged, checked for resuming, its variant row read and its
// replaceable entries listed. Bad input must end in corsa::InputError; nothing outside the
// scratch folder may be touched, and --force may list only entries inside the folder.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/core/json.h"
#include "corsa/sweep/merge.h"
#include "fuzz_parts.h"
#include "sweep_folder.h"

namespace {

namespace fs = std::filesystem;

// What `corsa sweep` would compare against: a plan hash and no shard.
const corsa::Json kDescription = {{"plan", "6c1b0a3f4e2d9c87"}, {"variants", 4}};
const std::vector<std::string> kHeader{
    "index",    "Ego_Speed",  "status",  "exit_status",  "end_reason",       "sim_time",
    "steps",    "collisions", "min_ttc", "min_distance", "max_deceleration", "error",
    "wall_time"};

void write_if_given(const fs::path& file, const std::string& bytes) {
  if (!bytes.empty()) corsa::fuzz::write_bytes(file, bytes);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const fs::path kScratch = corsa::fuzz::scratch_folder("sweep_folder_fuzz");
  const fs::path shard = kScratch / "shard";
  const fs::path merged = kScratch / "merged";
  const fs::path outside = kScratch / "outside.txt";
  std::error_code error;
  fs::remove_all(shard, error);
  fs::remove_all(merged, error);
  corsa::fuzz::write_bytes(outside, "not the sweep's");
  const auto parts = corsa::fuzz::split_parts(data, size, 4);
  fs::create_directories(shard / "variants" / "0");
  write_if_given(shard / "sweep.json", parts[0]);
  write_if_given(shard / "shard.json", parts[1]);
  write_if_given(shard / "summary.csv", parts[2]);
  write_if_given(shard / "variants" / "0" / "result.csv", parts[3]);

  try {
    (void)corsa::sweep::merge_sweeps(merged, {shard});
  } catch (const corsa::InputError&) {
  }
  try {
    corsa::sweep::detail::check_resumable(shard, kDescription, corsa::Json());
  } catch (const corsa::InputError&) {
  }
  try {
    (void)corsa::sweep::detail::finished_row(shard / "variants" / "0", 0, kHeader);
  } catch (const corsa::InputError&) {
  }
  try {
    for (const fs::path& entry : corsa::sweep::detail::replaceable_entries(shard)) {
      const fs::path relative = entry.lexically_relative(shard);
      if (relative.empty() || *relative.begin() == "..") std::abort();  // outside the folder
    }
  } catch (const corsa::InputError&) {
  }
  if (!fs::exists(outside, error)) std::abort();
  return 0;
}
