#pragma once

// The published scenarios of ../shared/conformance, found by content: scenarios, catalogs and
// parameter distributions (variation files) alike end in .xosc.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"

namespace corsa::test {

inline const std::filesystem::path kConformanceDir =
    std::filesystem::path(CORSA_SHARED_DIR) / "conformance";

/// Every .xosc under `folder` (recursively) whose text holds `marker` (e.g. "<Storyboard" for a
/// scenario, "<ParameterValueDistribution" for a variation file), sorted.
inline std::vector<std::filesystem::path> xosc_files(const std::filesystem::path& folder,
                                                     const std::string& marker) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xosc" &&
        read_file(entry.path()).find(marker) != std::string::npos) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace corsa::test
