#include "dataset_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "corsa/core/atomic_file.h"
#include "corsa/core/json.h"
#include "corsa/core/strings.h"

namespace corsa::test {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) { return corsa::read_file(path); }

// The objects of a labels file.
corsa::Json label_objects(const fs::path& file) {
  return corsa::read_json_file(file).at("objects");
}

// Every [x_min, y_min, x_max, y_max] "box_2d" of a labels file.
std::vector<std::array<double, 4>> boxes_2d(const fs::path& file) {
  std::vector<std::array<double, 4>> out;
  for (const corsa::Json& object : label_objects(file)) {
    if (object.contains("box_2d")) {
      out.push_back(object.at("box_2d").get<std::array<double, 4>>());
    }
  }
  return out;
}

// (instance id, lidar_points) of every object of a LiDAR labels file.
std::vector<std::pair<uint32_t, uint64_t>> lidar_objects(const fs::path& file) {
  std::vector<std::pair<uint32_t, uint64_t>> out;
  for (const corsa::Json& object : label_objects(file)) {
    out.emplace_back(object.at("instance_id").get<uint32_t>(),
                     object.at("lidar_points").get<uint64_t>());
  }
  return out;
}

int64_t header_count(const std::string& text, const std::string& key) {
  const size_t at = text.find(key);
  if (at == std::string::npos) {
    return -1;
  }
  return std::stoll(text.substr(at + key.size(), 20));
}

void check_lidar(const fs::path& dataset, const std::string& stem_path,
                 std::vector<std::string>& problems) {
  const auto size = [&](const std::string& ext) {
    return static_cast<int64_t>(fs::file_size(dataset / (stem_path + ext)));
  };
  const int64_t bin = size(".bin") / 16;  // float32 x y z intensity
  const int64_t label = size(".label") / 4;
  const int64_t ply = header_count(read_all(dataset / (stem_path + ".ply")), "element vertex ");
  const int64_t pcd = header_count(read_all(dataset / (stem_path + ".pcd")), "\nPOINTS ");
  if (bin != label || bin != ply || bin != pcd) {
    problems.push_back(stem_path + ": point counts differ (bin " + std::to_string(bin) +
                       ", label " + std::to_string(label) + ", ply " + std::to_string(ply) +
                       ", pcd " + std::to_string(pcd) + ")");
  }
  const std::string labels = read_all(dataset / (stem_path + ".label"));
  std::map<uint32_t, uint64_t> per_instance;
  for (size_t i = 0; i + 4 <= labels.size(); i += 4) {
    uint32_t v = 0;
    std::memcpy(&v, labels.data() + i, 4);
    ++per_instance[v >> 16];
  }
  for (const auto& [instance, points] : lidar_objects(dataset / (stem_path + "_labels.json"))) {
    if (per_instance[instance] != points) {
      problems.push_back(stem_path + ": object " + std::to_string(instance) + " has " +
                         std::to_string(points) + " points in its label but " +
                         std::to_string(per_instance[instance]) + " in the cloud");
    }
  }
}

}  // namespace

std::vector<IndexRow> read_index(const fs::path& dataset) {
  std::istringstream in(read_all(dataset / "frames.csv"));
  std::string line;
  std::getline(in, line);
  if (line != "capture,tick,time,sensor,frame,file,overlap") {
    throw std::runtime_error("bad frames.csv header: " + line);
  }
  std::vector<IndexRow> rows;
  while (std::getline(in, line)) {
    const auto f = corsa::split(line, ',');
    if (f.size() != 7) {
      throw std::runtime_error("bad frames.csv row: " + line);
    }
    rows.push_back({std::stoll(std::string(f[0])), std::stoll(std::string(f[1])),
                    std::stod(std::string(f[2])), std::string(f[3]), std::string(f[4]),
                    std::string(f[5]), std::stoll(std::string(f[6]))});
  }
  return rows;
}

std::vector<std::string> check_dataset(const fs::path& dataset, int width, int height) {
  std::vector<std::string> problems;
  const std::vector<IndexRow> rows = read_index(dataset);
  std::set<int64_t> captures;
  std::set<int64_t> with_pose;
  for (const IndexRow& row : rows) {
    captures.insert(row.capture);
    if (!fs::is_regular_file(dataset / row.file)) {
      problems.push_back("indexed file missing: " + row.file);
      continue;
    }
    if (row.sensor == "poses") {
      with_pose.insert(row.capture);
    }
    const std::string name = fs::path(row.file).filename().string();
    if (name.ends_with("_labels.json")) {
      for (const auto& b : boxes_2d(dataset / row.file)) {
        if (b[0] < -0.5 || b[1] < -0.5 || b[2] > width - 0.5 + 1e-9 || b[3] > height - 0.5 + 1e-9 ||
            b[0] > b[2] || b[1] > b[3]) {
          problems.push_back(row.file + ": 2D box outside the image");
        }
      }
    }
    if (name.ends_with(".bin")) {
      const std::string stem_path = row.file.substr(0, row.file.size() - 4);
      check_lidar(dataset, stem_path, problems);
    }
  }
  if (captures != with_pose) {
    problems.push_back("some captures have no pose file");
  }
  return problems;
}

std::vector<std::string> files_under(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) {
      out.push_back(fs::relative(entry.path(), dir).generic_string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

double json_number(const std::string& json, const std::string& key) {
  const corsa::Json document = corsa::parse_json(json, "run.json");
  const auto value = document.find(key);
  return value != document.end() && value->is_number() ? value->get<double>() : std::nan("");
}

std::string json_string(const std::string& json, const std::string& key) {
  const corsa::Json document = corsa::parse_json(json, "run.json");
  const auto value = document.find(key);
  return value != document.end() && value->is_string() ? value->get<std::string>() : "";
}

}  // namespace corsa::test
