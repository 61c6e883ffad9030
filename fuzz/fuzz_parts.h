#pragma once

// Helpers of the libFuzzer targets that read folders: one fuzz input holds several files, cut
// apart at kPartSeparator (listed in each target's dictionary, so that mutations keep it), and a
// scratch folder of the process's own under /dev/shm (or TMPDIR) to write them into.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace corsa::fuzz {

inline constexpr std::string_view kPartSeparator = "--corsa-fuzz-part--";

/// The input cut into exactly `count` parts (missing ones empty; the last takes the rest).
inline std::vector<std::string> split_parts(const uint8_t* data, size_t size, size_t count) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  while (parts.size() + 1 < count) {
    const size_t at = rest.find(kPartSeparator);
    if (at == std::string_view::npos) break;
    parts.emplace_back(rest.substr(0, at));
    rest.remove_prefix(at + kPartSeparator.size());
  }
  parts.emplace_back(rest);
  parts.resize(count);
  return parts;
}

/// Removes its folder when the process exits (libFuzzer ends with exit()).
struct RemovedAtExit {
  std::filesystem::path folder;
  ~RemovedAtExit() {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  }
};

/// A folder of this process's own, emptied, and removed at exit: /dev/shm (memory) when there is
/// one, else TMPDIR.
inline std::filesystem::path scratch_folder(const std::string& name) {
  std::error_code error;
  std::filesystem::path base = "/dev/shm";
  if (!std::filesystem::is_directory(base, error)) {
    const char* tmp = std::getenv("TMPDIR");
    base = tmp != nullptr ? tmp : "/tmp";
  }
  const std::filesystem::path folder = base / (name + "." + std::to_string(::getpid()));
  std::filesystem::remove_all(folder, error);
  std::filesystem::create_directories(folder);
  static std::vector<RemovedAtExit> made;
  made.push_back({folder});
  return folder;
}

inline void write_bytes(const std::filesystem::path& file, std::string_view bytes) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace corsa::fuzz
