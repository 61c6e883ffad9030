#pragma once

// Ground-truth labels of one sensor frame: 2D boxes (amodal and visible) with occlusion and
// truncation for cameras, 3D boxes in the sensor and map frames, class, instance and track id,
// and the LiDAR point count per object.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "corsa/sensors/box.h"
#include "corsa/sensors/camera_model.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/environment.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/lidar.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/static_mesh.h"

namespace corsa::sensors {

/// A vehicle light in a camera label, as the frame shows it (docs/datasets.md, "Vehicle
/// lights in the labels").
struct LightLabel {
  engine::VehicleLight light = engine::VehicleLight::kLowBeam;
  engine::LightMode mode = engine::LightMode::kOff;
  bool lit = false;  ///< emitting in this frame (a flashing light in its on phase)
  bool set = false;  ///< a LightStateAction set it (else the engine or the renderer chose it)
  std::optional<double> intensity_cd;        ///< luminousIntensity as set (cd)
  std::optional<std::array<double, 3>> rgb;  ///< Color as set: linear RGB, 0..1 each
};

/// A vehicle's lights in a camera label.
struct VehicleLightsLabel {
  /// The lights that are lit, flashing or set, by VehicleLight order.
  std::vector<LightLabel> lights;
  uint32_t lamps = 0;  ///< LightRole bits of the lamps its shape has and the frame lit
};

/// The label of an entity, or of a parked vehicle (a static object with its own box: no entity
/// name, its instance id as track id), as a camera or a LiDAR sees it.
struct ObjectLabel {
  uint32_t instance_id = 0;
  uint32_t track_id = 0;  ///< stable over the run: the entity's instance id in the engine
  std::string name;       ///< entity name ("" for a parked vehicle)
  bool parked = false;    ///< a parked vehicle (in the camera's static labels as well)
  std::string type;       ///< a parked vehicle's body style (sedan, hatchback, suv, van, pickup)
  SemanticClass semantic = SemanticClass::kUnlabeled;
  Box3 box_world;         ///< map frame
  Box3 box_sensor;        ///< camera optical frame (cameras) or sensor body frame (LiDAR)
  double distance = 0.0;  ///< metres from the sensor to the box centre
  // Cameras only:
  Box2 box_2d;              ///< the projected 3D box clipped to the image
  Box2 box_2d_visible;      ///< tight box around the object's visible pixels
  double truncation = 0.0;  ///< share of the projected box outside the image, 0..1
  double occlusion = 0.0;   ///< share of the object's silhouette hidden by others, 0..1
  uint64_t visible_pixels = 0;
  std::optional<VehicleLightsLabel> lights;  ///< vehicles only
  // LiDAR only:
  uint64_t lidar_points = 0;
};

/// A labelled static object seen by a camera: traffic lights with their state, signs with their
/// type (OpenDRIVE signals), street lights, trees and the like.
struct StaticObjectLabel {
  uint32_t instance_id = 0;
  /// What the object is when that is known (parked vehicles: car), else the class of most of
  /// its pixels (`static` without a semantic image).
  SemanticClass semantic = SemanticClass::kStatic;
  ObjectInfo info;
  std::string state;  ///< traffic lights: the signal's state string this frame ("" unknown)
  Box3 box_world;     ///< the object's own box (parked vehicles), else its axis-aligned bounds
  Box2 box_2d_visible;
  uint64_t visible_pixels = 0;
};

/// The static objects with object info that have visible pixels in an instance image (camera
/// order: by instance id).
std::vector<StaticObjectLabel> static_object_labels(const Scene& scene,
                                                    std::span<const uint32_t> instance, int width,
                                                    std::span<const uint8_t> semantic = {});

/// KITTI's discrete occlusion state from the occluded share: 0 fully visible (< 10%), 1 partly
/// (< 50%), 2 largely (< 90%), 3 unknown / almost fully occluded.
int kitti_occlusion_level(double occlusion);
/// KITTI rotation_y: yaw about the camera's y axis (down), 0 when the box faces the camera's x.
double kitti_rotation_y(const Box3& box_in_optical_frame);

/// Labels of a camera frame: every visible entity with at least one visible pixel, except the
/// entity with instance id `carrier` (the sensor's own vehicle; 0 for none), then every parked
/// vehicle with a visible pixel (by instance id).
/// `instance` is the camera's instance buffer (CameraImages::instance). Vehicles have their
/// lights as the frame lit by `lighting` draws them (null: a frame in daylight).
std::vector<ObjectLabel> camera_labels(const Scene& scene, const CameraRenderer& camera,
                                       const Rigid& world_from_body,
                                       std::span<const uint32_t> instance, uint32_t carrier = 0,
                                       const Lighting* lighting = nullptr);

/// Labels of a LiDAR frame: every visible entity whose centre is within `range_m`, except the
/// carrier, then every parked vehicle whose box centre is within `range_m` (by instance id).
std::vector<ObjectLabel> lidar_labels(const Scene& scene, const Rigid& world_from_sensor,
                                      const PointCloud& cloud, double range_m,
                                      uint32_t carrier = 0);

/// The image of a box (optical frame) through `camera`: the bounding rectangle of its corners
/// (and of its edges where they cross the near plane), unclipped; nothing when it is behind.
std::optional<Box2> projected_box(const CameraModel& camera, const Box3& box_in_optical_frame);

/// The 3D box of an entity in the map frame.
Box3 entity_box(const engine::EntitySnapshot& entity);

}  // namespace corsa::sensors
