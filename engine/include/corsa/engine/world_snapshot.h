#pragma once

// What the engine hands to a capture sink (the sensors) at a capture time: every entity's pose,
// box and motion, and the environment. The engine owns this interface so that it builds and is
// tested without Embree; the command line connects a sensors-side sink to it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace corsa::engine {

/// Position and orientation in map coordinates: metres; heading, pitch, roll in radians
/// (heading counter-clockwise from +x, OpenSCENARIO/OpenDRIVE conventions).
struct Pose {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double h = 0.0;
  double p = 0.0;
  double r = 0.0;
};

/// Entity categories from OpenSCENARIO's vehicleCategory, pedestrianCategory and
/// miscObjectCategory, collapsed to what sensors and labels distinguish.
enum class EntityCategory : uint8_t {
  kCar,
  kVan,
  kTruck,
  kTrailer,
  kSemitrailer,
  kBus,
  kMotorbike,
  kBicycle,
  kTrain,
  kTram,
  kPedestrian,
  kWheelchair,
  kAnimal,
  kObstacle,  ///< any MiscObject
};

/// OpenSCENARIO BoundingBox: centre relative to the entity's reference point (for vehicles the
/// rear axle centre on the ground), in the entity frame (x forward, y left, z up); dimensions.
struct Box {
  double center_x = 0.0;
  double center_y = 0.0;
  double center_z = 0.0;
  double length = 0.0;
  double width = 0.0;
  double height = 0.0;
};

/// Vehicle lights as bits of EntitySnapshot::lights_on / lights_set (OpenSCENARIO 1.2
/// VehicleLightType, in its order).
enum class VehicleLight : uint8_t {
  kDaytimeRunning,
  kLowBeam,
  kHighBeam,
  kFogLights,
  kFogLightsFront,
  kFogLightsRear,
  kBrake,
  kWarning,
  kIndicatorLeft,
  kIndicatorRight,
  kReversing,
  kLicensePlate,
  kSpecialPurpose,
};
inline constexpr uint32_t light_bit(VehicleLight light) {
  return 1u << static_cast<unsigned>(light);
}
inline constexpr size_t kVehicleLightTypes = 13;
/// OpenSCENARIO's names of the lights (vehicleLightType), by VehicleLight.
inline constexpr std::array<std::string_view, kVehicleLightTypes> kVehicleLightNames = {
    "daytimeRunningLights", "lowBeam",        "highBeam",        "fogLights",
    "fogLightsFront",       "fogLightsRear",  "brakeLights",     "warningLights",
    "indicatorLeft",        "indicatorRight", "reversingLights", "licensePlateIllumination",
    "specialPurposeLights"};

/// How a light is switched (OpenSCENARIO LightMode).
enum class LightMode : uint8_t { kOff, kOn, kFlashing };

/// A light as a LightStateAction set it: the values the scenario gave, for the labels and the
/// run summary (the sensors draw from lights_on and light_looks).
struct LightSettingView {
  VehicleLight light = VehicleLight::kLowBeam;
  LightMode mode = LightMode::kOn;
  std::optional<double> candela;  ///< luminousIntensity (cd); none: the lamp's own
  /// Color as linear RGB, 0..1 each (CMYK and a colorType alone converted, docs/engine.md);
  /// none: the lamp's own colour.
  std::optional<std::array<double, 3>> rgb;
  double since = 0.0;         ///< s, simulation time the action set it
  double transition_s = 0.0;  ///< transitionTime (s): the fade from the state before
  double on_s = 0.5;          ///< flashing: s lit per cycle
  double off_s = 0.5;         ///< flashing: s dark per cycle
};

/// How a light that a LightStateAction set with a luminous intensity, a colour or a transition
/// time emits (OpenSCENARIO 1.2 LightState), as a sum of parts in linear RGB whose luminance
/// (Rec. 709 weights) is their intensity in cd: a fade mixes two states linearly, so every mix
/// is such a sum. With the lamp's own intensity I0 (cd) and colour h (luminance 1) the light
/// emits fixed_cd + lamp_colour_cd * h + I0 * (colour_share + lamp_share * h); a light set
/// without any of the three has no look and emits I0 * h when lit.
struct LightLook {
  VehicleLight light = VehicleLight::kLowBeam;
  std::array<double, 3> fixed_cd{};      ///< given colours at given intensities (cd)
  double lamp_colour_cd = 0.0;           ///< the lamp's colour at given intensities (cd)
  std::array<double, 3> colour_share{};  ///< given colours at the lamp's intensity (share of I0)
  double lamp_share = 0.0;               ///< the lamp as it is (share of I0 * h)
};

/// An animation state of an entity (AnimationAction, OpenSCENARIO 1.3 §7.4.7.2).
struct AnimationSnapshot {
  /// "doorFrontLeft", ... (components), "walking", ... (pedestrian motions), a user-defined type
  /// or an animation file's path.
  std::string type;
  double state = 0.0;  ///< 0 .. 1 (AnimationState), following animationDuration
};

struct EntitySnapshot {
  uint32_t instance_id = 0;  ///< stable for the whole run, 1-based in document order
  std::string name;
  EntityCategory category = EntityCategory::kCar;
  std::string model3d;  ///< OpenSCENARIO model3d attribute, may be empty
  Pose pose;
  Box box;
  double speed = 0.0;  ///< m/s along the heading
  /// World-frame velocity (m/s) and yaw rate (rad/s), e.g. for motion blur.
  double vx = 0.0, vy = 0.0, vz = 0.0, yaw_rate = 0.0;
  double acceleration = 0.0;  ///< m/s^2 along the heading over the last step
  double odometer = 0.0;      ///< m travelled since the start (turns wheels, drives walk cycles)
  /// Lights lit at this tick (bits of VehicleLight; flashing ones in their on phase): brake
  /// lights while decelerating or held at a stop, indicators while the entity moves sideways
  /// across its lane, and whatever LightStateAction set.
  uint32_t lights_on = 0;
  /// Lights a LightStateAction set (on, off or flashing): the sensors leave these alone, and
  /// choose the others themselves (headlights when it is dark).
  uint32_t lights_set = 0;
  /// Lights in a flashing mode, in their on phase or not: LightStateAction's flashing ones and
  /// the indicator the engine flashes while the entity moves across its lane.
  uint32_t lights_flashing = 0;
  /// The lights of lights_set as the scenario set them, by VehicleLight order.
  std::vector<LightSettingView> light_settings;
  /// The lights of lights_set with a luminous intensity, a colour or a fade, by VehicleLight
  /// order; a lit bit of lights_on then means the look emits something.
  std::vector<LightLook> light_looks;
  /// VisibilityAction's sensors flag: whether the sensors see the entity (false while it is
  /// absent), except those named in sensor_exceptions.
  bool visible = true;
  /// VisibilityAction's SensorReferenceSet (OpenSCENARIO 1.3 §7.4.5): the sensors (rig names)
  /// for which the opposite of `visible` holds. Empty: `visible` holds for every sensor.
  std::vector<std::string> sensor_exceptions;
  std::vector<AnimationSnapshot> animations;  ///< by type name
};

/// Whether the sensor named `sensor` sees `entity` (EntitySnapshot::visible and its exceptions).
inline bool visible_to(const EntitySnapshot& entity, std::string_view sensor) {
  for (const std::string& name : entity.sensor_exceptions) {
    if (name == sensor) {
      return !entity.visible;
    }
  }
  return entity.visible;
}

enum class PrecipitationType : uint8_t { kDry, kRain, kSnow };

/// The environment at the capture time (OpenSCENARIO Environment, possibly overridden on the
/// command line).
struct EnvironmentState {
  int year = 2024, month = 6, day = 21;  ///< local date, for the solar position
  double time_of_day = 12.0 * 3600.0;    ///< seconds since local midnight
  /// Local time minus UTC, hours. Nothing when the scenario's dateTime has no zone (or there is
  /// no TimeOfDay): the time is then local solar time at the map's place (12:00 = the sun due
  /// south or north, at its highest).
  std::optional<double> utc_offset_hours;
  /// Sun from OpenSCENARIO Weather/Sun when given (radians: azimuth from north clockwise as the
  /// standard defines it, elevation above the horizon); otherwise computed from date, time and the
  /// map's georeference.
  std::optional<double> sun_azimuth;
  std::optional<double> sun_elevation;
  double sun_intensity = 100000.0;                                    ///< lux
  double fog_visual_range = std::numeric_limits<double>::infinity();  ///< metres
  PrecipitationType precipitation = PrecipitationType::kDry;
  double precipitation_intensity = 0.0;  ///< mm/h
  double cloud_cover = 0.0;              ///< 0 (clear) .. 1 (overcast)
  double wind_speed = 0.0;               ///< m/s
  double wind_direction = 0.0;           ///< radians
  double road_friction_scale = 1.0;
  bool wet_road = false;
};

/// A traffic signal's state (OpenSCENARIO TrafficSignalState: the OpenDRIVE signal id and its
/// state string, e.g. "off;off;on").
struct SignalSnapshot {
  std::string id;
  std::string state;
};

struct WorldSnapshot {
  int64_t tick = 0;   ///< integer step count since the start
  double time = 0.0;  ///< seconds, tick * dt
  std::vector<EntitySnapshot> entities;
  EnvironmentState environment;
  std::vector<SignalSnapshot> signals;  ///< by id
  /// Entities whose boxes interpenetrate now: pairs of instance ids (smaller first), sorted.
  std::vector<std::pair<uint32_t, uint32_t>> overlaps;
};

/// Receives the world at capture times. `sensors` names the sensors due at this time.
class CaptureSink {
 public:
  virtual ~CaptureSink() = default;
  virtual void capture(const WorldSnapshot& world, std::span<const std::string> sensors) = 0;
};

}  // namespace corsa::engine
