// corsa.read_trajectory's work: a binary trajectory (`corsa run --record FILE.corsatraj`) read by
// engine::TrajectoryReader into one numpy structured array, without a Python object per row.

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstddef>
#include <cstring>
#include <vector>

#include "bindings.h"
#include "corsa/engine/trajectory_file.h"
#include "numpy_dtype.h"

namespace corsa::python {
namespace py = pybind11;
namespace {

/// One row of the array: the numbers of one trajectory CSV row.
struct TrajectoryRecord {
  int64_t tick;
  double time, x, y, z, h, p, r, speed, s, t;
  uint32_t entity, road;
  int32_t lane;
  uint8_t on_road;
  uint8_t padding[3];
};
static_assert(sizeof(TrajectoryRecord) == 104);

py::dtype trajectory_dtype() {
  return record_dtype(
      {
          {"tick", "<i8", offsetof(TrajectoryRecord, tick)},
          {"time", "<f8", offsetof(TrajectoryRecord, time)},
          {"entity", "<u4", offsetof(TrajectoryRecord, entity)},
          {"x", "<f8", offsetof(TrajectoryRecord, x)},
          {"y", "<f8", offsetof(TrajectoryRecord, y)},
          {"z", "<f8", offsetof(TrajectoryRecord, z)},
          {"h", "<f8", offsetof(TrajectoryRecord, h)},
          {"p", "<f8", offsetof(TrajectoryRecord, p)},
          {"r", "<f8", offsetof(TrajectoryRecord, r)},
          {"speed", "<f8", offsetof(TrajectoryRecord, speed)},
          {"on_road", "?", offsetof(TrajectoryRecord, on_road)},
          {"road", "<u4", offsetof(TrajectoryRecord, road)},
          {"lane", "<i4", offsetof(TrajectoryRecord, lane)},
          {"s", "<f8", offsetof(TrajectoryRecord, s)},
          {"t", "<f8", offsetof(TrajectoryRecord, t)},
      },
      sizeof(TrajectoryRecord));
}

py::dict read_trajectory(const std::filesystem::path& path) {
  std::vector<TrajectoryRecord> records;
  std::vector<std::string> entities, roads;
  double dt = 0.0;
  int64_t every = 1;
  {
    py::gil_scoped_release nogil;
    engine::TrajectoryReader reader(path);
    dt = reader.dt();
    every = reader.every();
    for (size_t i = 0; i < reader.entity_count(); ++i) {
      entities.push_back(reader.entity_name(static_cast<uint32_t>(i)));
    }
    for (size_t i = 0; i < reader.road_count(); ++i) {
      roads.push_back(reader.road_id(static_cast<uint32_t>(i)));
    }
    engine::TrajectoryFrame frame;
    while (reader.next(frame)) {
      for (const engine::TrajectoryRow& row : frame.rows) {
        TrajectoryRecord r{};
        r.tick = frame.tick;
        r.time = frame.time;
        r.entity = row.entity;
        r.x = row.x;
        r.y = row.y;
        r.z = row.z;
        r.h = row.h;
        r.p = row.p;
        r.r = row.r;
        r.speed = row.speed;
        r.on_road = row.on_road ? 1 : 0;
        r.road = row.road;
        r.lane = row.lane;
        r.s = row.s;
        r.t = row.t;
        records.push_back(r);
      }
    }
  }
  py::array rows(trajectory_dtype(),
                 std::vector<py::ssize_t>{static_cast<py::ssize_t>(records.size())});
  if (!records.empty()) {
    std::memcpy(rows.mutable_data(), records.data(), records.size() * sizeof(TrajectoryRecord));
  }
  py::dict out;
  out["dt"] = dt;
  out["every"] = every;
  out["entities"] = entities;
  out["roads"] = roads;
  out["rows"] = rows;
  return out;
}

}  // namespace

void bind_trajectory(py::module_& m) {
  m.def("_read_trajectory", &read_trajectory, py::arg("path"));
}

}  // namespace corsa::python
