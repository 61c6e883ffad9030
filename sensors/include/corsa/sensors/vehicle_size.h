#pragma once

// How large a vehicle the generated models draw with their details.

#include "corsa/engine/world_snapshot.h"

namespace corsa::sensors {

/// The largest box the vehicle generators detail (lamps, grilles, windows, mirrors, wheels):
/// they build details in pieces of a fixed real size (15 cm lamp pieces, 1.35 m windows), so
/// their cost grows with the box, to minutes at 60 m and past any memory at 1e7 m. No road
/// vehicle is longer than 60 m (road trains reach 53.5 m), wider than 6 m or higher than 8 m;
/// trains and trams may be 1 km long. A larger (or not finite) box gets a plain box model of
/// its size and semantic class.
struct DetailedVehicleLimits {
  static constexpr double kRoadLength = 60.0;    ///< m, cars, vans, trucks, trailers, buses
  static constexpr double kRailLength = 1000.0;  ///< m, trains and trams
  static constexpr double kWidth = 6.0;          ///< m
  static constexpr double kHeight = 8.0;         ///< m
};

/// Whether a generated model of `category` with `box` is too large for its details: true only
/// for vehicles (the other models do not grow in cost with their size).
inline bool vehicle_too_large_for_details(engine::EntityCategory category, const engine::Box& box) {
  using engine::EntityCategory;
  double longest = DetailedVehicleLimits::kRoadLength;
  switch (category) {
    case EntityCategory::kCar:
    case EntityCategory::kVan:
    case EntityCategory::kTruck:
    case EntityCategory::kTrailer:
    case EntityCategory::kSemitrailer:
    case EntityCategory::kBus:
      break;
    case EntityCategory::kTrain:
    case EntityCategory::kTram:
      longest = DetailedVehicleLimits::kRailLength;
      break;
    default:
      return false;
  }
  // Written so that a NaN dimension counts as too large.
  return !(box.length <= longest && box.width <= DetailedVehicleLimits::kWidth &&
           box.height <= DetailedVehicleLimits::kHeight);
}

}  // namespace corsa::sensors
