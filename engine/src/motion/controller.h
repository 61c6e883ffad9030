#pragma once

// Controllers move entities (OpenSCENARIO 1.3 §7.5 "Controllers"): every step each entity's
// controller turns what the running actions ask for (Entity::speed_command and
// lateral_command) into motion over dt. The default controller is ideal: it follows the
// commands exactly along the lanes. Car following and vehicle dynamics (controllers/) are built
// on it; controllers/controllers.h picks each entity's controller every step.

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "corsa/xodr/map.h"
#include "state/entity.h"

namespace corsa::engine::detail {

/// Curvatures (1/m) of reference lines that the default controller's steps read (its path
/// scale, motion/default_controller.cpp), by road and s: a car that creeps (a speed whose step no
/// longer changes the bits of its s) reads the curvature at the same s every step, and on a
/// cubic reference line each reading is an evaluation. The map does not change during a run, so
/// the same road and s have the same curvature; a slot holds the last pair that hashed to it.
class CurvatureMemo {
 public:
  /// The curvature at (road, s) from the slot's pair when it is that one, else from `read`.
  template <typename Read>
  double at(uint32_t road, double s, const Read& read) {
    const uint64_t bits = std::bit_cast<uint64_t>(s);
    Slot& slot = slots_[((bits ^ road) * 0x9E3779B97F4A7C15ull) >> (64 - kSlotBits)];
    if (!slot.valid || slot.road != road || slot.s_bits != bits) {
      slot = {true, road, bits, read()};
    }
    return slot.curvature;
  }

 private:
  static constexpr int kSlotBits = 5;
  struct Slot {
    bool valid = false;
    uint32_t road = 0;
    uint64_t s_bits = 0;  ///< s (m), compared bit for bit
    double curvature = 0.0;
  };
  std::array<Slot, size_t{1} << kSlotBits> slots_{};
};

struct MotionContext {
  const xodr::Map* map = nullptr;  ///< null: no road network, entities move freely
  double dt = 0.01;                ///< s
  std::vector<xodr::LaneSpan>* scratch = nullptr;
  /// Scratch for the neighbour queries of generated traffic (entity indices), one per thread.
  std::vector<uint32_t>* nearby = nullptr;
  /// One per thread; null: the curvature is read from the map every time.
  CurvatureMemo* curvatures = nullptr;
  /// A scenario without road network: the default controller has no road to move an entity
  /// along, so the entity stands (0 m/s) unless an action moves it itself (a trajectory's pose
  /// commands), as in esmini.
  bool stand_without_roads = false;
};

class Controller {
 public:
  virtual ~Controller() = default;
  virtual void step(Entity& entity, const MotionContext& context) const = 0;
};

/// The entity's memos of the map's answers that a step may consult (they give what the map
/// would: update_pose_from_lane and locate_near below).
struct MapMemos {
  LanePoseMemo& lane_pose;
  PointLocateMemo& point;
};

/// The default controller: along the followed lane at the commanded speed (a step travels the
/// speed at its end times dt, semi-implicit Euler), lateral offset as commanded, heading following
/// the road plus the angle of the lateral motion; off the road straight along the heading (without
/// any road network, standing: MotionContext::stand_without_roads). An
/// entity that reaches a lane end without successor stops there (EndOfRoadCondition).
class DefaultController final : public Controller {
 public:
  void step(Entity& entity, const MotionContext& context) const override;

 private:
  /// The step itself, given only the entity's motion and its memos of the map's answers;
  /// `stood`: it moved neither along its lane nor across it.
  void step_entity(EntityMotion& entity, MapMemos memos, const MotionContext& context,
                   bool& stood) const;
};

/// Recomputes an entity's pose and road coordinates from its LaneFollow (after a teleport or a
/// move), or its road coordinates from its pose when it is off the lanes.
void update_pose_from_lane(Entity& entity, const xodr::Map& map,
                           std::vector<xodr::LaneSpan>& scratch);
void update_pose_from_lane(EntityMotion& entity, LanePoseMemo& memo, const xodr::Map& map,
                           std::vector<xodr::LaneSpan>& scratch);
void update_road_from_pose(Entity& entity, const xodr::Map* map);
void update_road_from_pose(EntityMotion& entity, PointLocateMemo& memo, const xodr::Map* map);
/// The same with the map's answer for the entity's point (state.pose.x, y) already at hand:
/// `located`, from locate_near.
void update_road_from_located(EntityMotion& entity,
                              const std::optional<xodr::LanePosition>& located);

/// The lane holding the point (x, y), or the nearest within 0.5 m (xodr::Map::locate with
/// max_distance 0.5): asked again for the same point, or for a point near one that had no
/// answer and still clear of every lane, the entity's memo answers (PointLocateMemo) without
/// searching the map.
const std::optional<xodr::LanePosition>& locate_near(Entity& entity, const xodr::Map& map, double x,
                                                     double y);
const std::optional<xodr::LanePosition>& locate_near(PointLocateMemo& memo, const xodr::Map& map,
                                                     double x, double y);
/// The road surface (xodr::surface_pose: z, pitch, roll) at the lane point locate_near gives for
/// (x, y) when it lies within `max_distance` m (road_point_within), else null. The surface
/// follows from the map's answer alone, so the memo keeps it with the answer.
const xodr::SurfacePose* surface_near(Entity& entity, const xodr::Map& map, double x, double y,
                                      double max_distance);
/// Whether locate_near would answer nothing for (x, y) from the memo alone (a point clear of
/// every lane), leaving the memo as it is.
inline bool clear_of_lanes_at(const PointLocateMemo& memo, double x, double y) {
  return memo.valid && !memo.located && std::abs(x - memo.x) <= memo.clear &&
         std::abs(y - memo.y) <= memo.clear;
}

}  // namespace corsa::engine::detail
