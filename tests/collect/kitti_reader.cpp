// KITTI format reader for the tests (kitti_reader.h).

#include "kitti_reader.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace corsa::test::kitti {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& file, int line, const std::string& what) {
  throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + what);
}

template <size_t N>
std::array<double, N> numbers(std::istringstream& in, const fs::path& file, int line) {
  std::array<double, N> out{};
  for (double& v : out) {
    if (!(in >> v)) {
      fail(file, line, "expected " + std::to_string(N) + " numbers");
    }
  }
  return out;
}

}  // namespace

std::vector<Object> read_labels(const fs::path& file) {
  static const std::set<std::string> kTypes{
      "Car", "Van", "Truck", "Pedestrian", "Person_sitting", "Cyclist", "Tram", "Misc", "DontCare"};
  std::ifstream in(file);
  if (!in) {
    fail(file, 0, "cannot read");
  }
  std::vector<Object> objects;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream fields(text);
    Object o;
    if (!(fields >> o.type >> o.truncated >> o.occluded >> o.alpha)) {
      fail(file, line, "expected type, truncated, occluded, alpha");
    }
    const auto box = numbers<4>(fields, file, line);
    const auto rest = numbers<7>(fields, file, line);
    std::string extra;
    if (fields >> extra) {
      fail(file, line, "more than 15 fields (a score belongs to results, not labels)");
    }
    o.box = box;
    o.dimensions = {rest[0], rest[1], rest[2]};
    o.location = {rest[3], rest[4], rest[5]};
    o.rotation_y = rest[6];
    if (kTypes.count(o.type) == 0) {
      fail(file, line, "unknown type '" + o.type + "'");
    }
    if (o.type == "DontCare") {
      if (o.truncated != -1 || o.occluded != -1 || o.alpha != -10 || o.location[0] != -1000) {
        fail(file, line, "a DontCare line has -1 -1 -10 ... -1000 -1000 -1000 -10");
      }
    } else {
      if (o.truncated < 0 || o.truncated > 1 || o.occluded < 0 || o.occluded > 3 ||
          std::fabs(o.alpha) > M_PI + 1e-2 || std::fabs(o.rotation_y) > M_PI + 1e-2 ||
          o.dimensions[0] <= 0 || o.dimensions[1] <= 0 || o.dimensions[2] <= 0) {
        fail(file, line, "a field out of its range");
      }
    }
    if (o.box[0] > o.box[2] || o.box[1] > o.box[3]) {
      fail(file, line, "box with left > right or top > bottom");
    }
    objects.push_back(o);
  }
  return objects;
}

Calib read_calib(const fs::path& file) {
  std::ifstream in(file);
  if (!in) {
    fail(file, 0, "cannot read");
  }
  Calib calib;
  std::set<std::string> seen;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream fields(text);
    std::string key;
    fields >> key;
    seen.insert(key);
    if (key == "P2:") {
      calib.p2 = numbers<12>(fields, file, line);
    } else if (key == "R0_rect:") {
      calib.r0_rect = numbers<9>(fields, file, line);
    } else if (key == "Tr_velo_to_cam:") {
      calib.tr_velo_to_cam = numbers<12>(fields, file, line);
    } else if (key == "P0:" || key == "P1:" || key == "P3:" || key == "Tr_imu_to_velo:") {
      numbers<12>(fields, file, line);
    } else {
      fail(file, line, "unknown key '" + key + "'");
    }
  }
  for (const char* key :
       {"P0:", "P1:", "P2:", "P3:", "R0_rect:", "Tr_velo_to_cam:", "Tr_imu_to_velo:"}) {
    if (seen.count(key) == 0) {
      fail(file, line, std::string("missing ") + key);
    }
  }
  return calib;
}

std::vector<Point> read_velodyne(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    fail(file, 0, "cannot read");
  }
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() % 16 != 0) {
    fail(file, 0, "not a whole number of float32 x y z reflectance records");
  }
  std::vector<Point> points(bytes.size() / 16);
  for (size_t i = 0; i < points.size(); ++i) {
    std::memcpy(&points[i], bytes.data() + 16 * i, 16);
  }
  return points;
}

std::vector<std::string> read_image_set(const fs::path& file) {
  std::ifstream in(file);
  if (!in) {
    fail(file, 0, "cannot read");
  }
  std::vector<std::string> ids;
  for (std::string id; std::getline(in, id);) {
    if (id.size() != 6 || id.find_first_not_of("0123456789") != std::string::npos) {
      fail(file, static_cast<int>(ids.size()) + 1, "an id is six digits");
    }
    ids.push_back(id);
  }
  return ids;
}

std::array<double, 3> velo_to_rect(const Calib& c, const Point& p) {
  const double v[4] = {p.x, p.y, p.z, 1.0};
  double cam[3];
  for (int r = 0; r < 3; ++r) {
    cam[r] = 0.0;
    for (int k = 0; k < 4; ++k) {
      cam[r] += c.tr_velo_to_cam[4 * r + k] * v[k];
    }
  }
  std::array<double, 3> out{};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      out[r] += c.r0_rect[3 * r + k] * cam[k];
    }
  }
  return out;
}

bool project(const Calib& c, const std::array<double, 3>& p, double& u, double& v) {
  const double x = c.p2[0] * p[0] + c.p2[1] * p[1] + c.p2[2] * p[2] + c.p2[3];
  const double y = c.p2[4] * p[0] + c.p2[5] * p[1] + c.p2[6] * p[2] + c.p2[7];
  const double w = c.p2[8] * p[0] + c.p2[9] * p[1] + c.p2[10] * p[2] + c.p2[11];
  if (w <= 1e-3) {
    return false;
  }
  u = x / w;
  v = y / w;
  return true;
}

std::array<std::array<double, 3>, 8> corners(const Object& o) {
  // The devkit's computeBox3D: y points down, the location is the bottom face's centre.
  const double h = o.dimensions[0], w = o.dimensions[1], l = o.dimensions[2];
  const double xs[8] = {l / 2, l / 2, -l / 2, -l / 2, l / 2, l / 2, -l / 2, -l / 2};
  const double ys[8] = {0, 0, 0, 0, -h, -h, -h, -h};
  const double zs[8] = {w / 2, -w / 2, -w / 2, w / 2, w / 2, -w / 2, -w / 2, w / 2};
  const double c = std::cos(o.rotation_y), s = std::sin(o.rotation_y);
  std::array<std::array<double, 3>, 8> out{};
  for (int i = 0; i < 8; ++i) {
    out[i] = {c * xs[i] + s * zs[i] + o.location[0], ys[i] + o.location[1],
              -s * xs[i] + c * zs[i] + o.location[2]};
  }
  return out;
}

bool inside(const Object& o, const std::array<double, 3>& p, double margin) {
  const double dx = p[0] - o.location[0];
  const double dy = p[1] - o.location[1];
  const double dz = p[2] - o.location[2];
  const double c = std::cos(o.rotation_y), s = std::sin(o.rotation_y);
  const double x = c * dx - s * dz;  // into the box frame (inverse of corners())
  const double z = s * dx + c * dz;
  return std::fabs(x) <= o.dimensions[2] / 2 + margin &&
         std::fabs(z) <= o.dimensions[1] / 2 + margin && dy <= margin &&
         dy >= -o.dimensions[0] - margin;
}

}  // namespace corsa::test::kitti
