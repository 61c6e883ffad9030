#pragma once

// Reads a dataset folder back for the tests: the index, the files it names, labels and point
// counts.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace corsa::test {

struct IndexRow {
  int64_t capture = 0;
  int64_t tick = 0;
  double time = 0.0;
  std::string sensor;
  std::string frame;
  std::string file;
  int64_t overlap = 0;  ///< entity pairs interpenetrating at the capture
};

/// frames.csv rows (the header is checked).
std::vector<IndexRow> read_index(const std::filesystem::path& dataset);

/// Every problem found: indexed files missing, captures without their pose file, 2D boxes
/// outside the image, point counts that disagree between PLY, PCD, BIN, label files and the
/// LiDAR labels. Empty when the dataset is consistent.
std::vector<std::string> check_dataset(const std::filesystem::path& dataset, int image_width,
                                       int image_height);

/// Every regular file under `dir`, relative, sorted.
std::vector<std::string> files_under(const std::filesystem::path& dir);

/// A top-level number member of a JSON object's text (run.json); NaN when absent.
double json_number(const std::string& json, const std::string& key);
/// A top-level string member of a JSON object's text (run.json); empty when absent.
std::string json_string(const std::string& json, const std::string& key);

}  // namespace corsa::test
