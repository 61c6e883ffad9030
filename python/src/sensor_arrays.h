#pragma once

// Sensor frames as numpy arrays, the layout corsa.Dataset reads back from the files (docs/
// python.md, "Arrays"):
//   RGB and bird's-eye cameras  uint8 (height, width, 3), R G B
//   depth                       float32 (height, width), metres along the optical axis, 0: none
//   semantic                    uint16 (height, width), class ids
//   instance                    uint16 (height, width), instance ids (above 65535: 65535)
//   LiDAR                       structured (points,): x y z intensity (float32, sensor body frame,
//                               m), ring (uint16), class (uint16), instance (uint32), time
//                               (float64, s: the capture time; one revolution is one instant)

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/sensor_system.h"

namespace corsa::python {

/// The sensor's own output of a frame, as above.
pybind11::array frame_array(const sensors::SensorFrame& frame);
/// A rigid transform as a 4 x 4 float64 matrix.
pybind11::array rigid_array(const sensors::Rigid& transform);
/// Every entity of a world snapshot as a dict with the keys of a dataset's pose file
/// (instance_id, name, category, pose [x y z h p r], box [cx cy cz l w h], speed, velocity,
/// yaw_rate, visible).
pybind11::list entity_dicts(const engine::WorldSnapshot& world);

}  // namespace corsa::python
