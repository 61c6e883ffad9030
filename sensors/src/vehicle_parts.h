#pragma once

// Parts every generated vehicle shares (private): paint drawn with real-world colour shares,
// wheels on bones that turn with the distance driven and steer with the yaw rate, lamps as
// emissive materials switched by the light state, licence plates and mirrors.

#include <functional>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/engine/world_snapshot.h"
#include "mesh_builder.h"

namespace corsa::sensors::detail {

/// Car paint drawn from the global shares of new cars (Axalta Global Automotive Color Popularity
/// Report 2022: white 34%, black 21%, grey 19%, silver 8%, blue 8%, red 5%, green 1%, other
/// colours 4%).
Material draw_car_paint(RandomStream& rng);
/// Paint of buses and trucks: white and a few fleet colours.
Material draw_fleet_paint(RandomStream& rng);

/// Shared materials of vehicles.
Material tyre_material();
Material rim_material();
Material trim_material();  ///< black plastic: bumpers, grilles, mirrors' housings, underbody
Material vehicle_glass();
Material headlamp_material();
Material tail_lamp_material();
Material brake_lamp_material();
Material indicator_material(bool left);
Material reversing_lamp_material();

/// One wheel of a vehicle: where it is and how it moves.
struct WheelSpec {
  Vec3 centre;           ///< entity frame, m
  double radius = 0.32;  ///< m
  double width = 0.22;   ///< m
  bool steers = false;
  uint8_t bone = 1;
  bool dual = false;  ///< twin tyres (truck rear axles)
};

/// Adds a wheel (tyre with rounded shoulders, rim with spokes so that its turning shows, hub)
/// on its bone. `outward` is +1 for a wheel on the left (y > 0), -1 on the right.
void add_wheel(MeshBuilder& b, const WheelSpec& wheel, int outward, int spokes);

/// Bone transforms of a wheeled vehicle: bone 0 fixed, each wheel turned by odometer / radius
/// about its axle and, if it steers, by the bicycle-model angle atan(wheelbase * yaw rate /
/// speed) (at most 35 degrees) about its vertical.
std::function<void(const engine::EntitySnapshot&, std::vector<Rigid>&)> wheel_pose(
    std::vector<WheelSpec> wheels, double wheelbase, size_t bones);

/// A lamp: a thin box whose front face, `size` (y, z) wide, faces along `facing` (+1 forward,
/// -1 backward) at x = `x_face`.
void add_lamp(MeshBuilder& b, const Material& m, double x_face, double y, double z, double size_y,
              double size_z, int facing);

/// A licence plate (520 x 110 mm, the EU and Korean long format) facing forward (+1) or
/// backward (-1) at x = `x_face`, centred at (y, z); characters drawn from `rng`.
void add_plate(MeshBuilder& b, double x_face, double y, double z, int facing, RandomStream& rng);

}  // namespace corsa::sensors::detail
