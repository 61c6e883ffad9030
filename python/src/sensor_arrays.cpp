#include "sensor_arrays.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "numpy_dtype.h"

namespace corsa::python {
namespace py = pybind11;
namespace {

template <typename T>
py::array image(int width, int height, int channels, const T* data) {
  std::vector<py::ssize_t> shape{height, width};
  if (channels > 1) shape.push_back(channels);
  py::array_t<T> out(shape);
  std::memcpy(out.mutable_data(), data, sizeof(T) * static_cast<size_t>(width) * height * channels);
  return out;
}

template <typename From>
py::array image_u16(int width, int height, const std::vector<From>& values) {
  py::array_t<uint16_t> out(std::vector<py::ssize_t>{height, width});
  uint16_t* data = out.mutable_data();
  for (size_t i = 0; i < values.size(); ++i) {
    data[i] = static_cast<uint16_t>(std::min<uint32_t>(values[i], 65535u));
  }
  return out;
}

struct LidarRecord {
  float x, y, z, intensity;
  uint16_t ring, label;
  uint32_t instance;
  double time;
};
static_assert(sizeof(LidarRecord) == 32);

py::dtype lidar_dtype() {
  return record_dtype(
      {
          {"x", "<f4", offsetof(LidarRecord, x)},
          {"y", "<f4", offsetof(LidarRecord, y)},
          {"z", "<f4", offsetof(LidarRecord, z)},
          {"intensity", "<f4", offsetof(LidarRecord, intensity)},
          {"ring", "<u2", offsetof(LidarRecord, ring)},
          {"class", "<u2", offsetof(LidarRecord, label)},
          {"instance", "<u4", offsetof(LidarRecord, instance)},
          {"time", "<f8", offsetof(LidarRecord, time)},
      },
      sizeof(LidarRecord));
}

py::array lidar(const sensors::SensorFrame& frame) {
  const auto& points = frame.cloud.points;
  py::array out(lidar_dtype(), std::vector<py::ssize_t>{static_cast<py::ssize_t>(points.size())});
  auto* records = static_cast<LidarRecord*>(out.mutable_data());
  for (size_t i = 0; i < points.size(); ++i) {
    const sensors::LidarPoint& p = points[i];
    records[i] = LidarRecord{p.x,           p.y,       p.z,
                             p.intensity,   p.ring,    static_cast<uint16_t>(p.semantic),
                             p.instance_id, frame.time};
  }
  return out;
}

}  // namespace

py::array frame_array(const sensors::SensorFrame& frame) {
  const sensors::CameraImages& c = frame.camera;
  switch (frame.kind) {
    case sensors::SensorKind::kRgbCamera:
      return image(c.width, c.height, 3, c.rgb.data());
    case sensors::SensorKind::kDepthCamera:
      return image(c.width, c.height, 1, c.depth.data());
    case sensors::SensorKind::kSemanticCamera:
      return image_u16(c.width, c.height, c.semantic);
    case sensors::SensorKind::kInstanceCamera:
      return image_u16(c.width, c.height, c.instance);
    case sensors::SensorKind::kBirdsEyeCamera:
      return image(frame.birds_eye.width, frame.birds_eye.height, 3, frame.birds_eye.rgb.data());
    case sensors::SensorKind::kLidar:
      return lidar(frame);
  }
  return py::array();
}

py::array rigid_array(const sensors::Rigid& t) {
  py::array_t<double> out(std::vector<py::ssize_t>{4, 4});
  double* m = out.mutable_data();
  const double translation[3] = {t.translation.x, t.translation.y, t.translation.z};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) m[r * 4 + k] = t.rotation.m[r][k];
    m[r * 4 + 3] = translation[r];
  }
  m[12] = m[13] = m[14] = 0.0;
  m[15] = 1.0;
  return out;
}

py::list entity_dicts(const engine::WorldSnapshot& world) {
  py::list out;
  for (const engine::EntitySnapshot& e : world.entities) {
    py::dict d;
    d["instance_id"] = e.instance_id;
    d["name"] = e.name;
    d["category"] = static_cast<int>(e.category);
    // Lists, as json.loads gives them from a dataset's pose file.
    d["pose"] = std::vector<double>{e.pose.x, e.pose.y, e.pose.z, e.pose.h, e.pose.p, e.pose.r};
    d["box"] = std::vector<double>{e.box.center_x, e.box.center_y, e.box.center_z,
                                   e.box.length,   e.box.width,    e.box.height};
    d["speed"] = e.speed;
    d["velocity"] = std::vector<double>{e.vx, e.vy, e.vz};
    d["yaw_rate"] = e.yaw_rate;
    d["visible"] = e.visible;
    out.append(std::move(d));
  }
  return out;
}

}  // namespace corsa::python
