// Generated vehicles giving way in junctions (controllers/give_way.h).

#include "controllers/give_way.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kHorizonBase = 12.0;  // m ahead of the front a zone is always claimed from
constexpr double kStandstill = 3.0;    // m the acc controller keeps to a standing leader
constexpr double kCleared = 1.0;       // m past a zone's far end that its rear has left it
// m: a vehicle standing at its stop point may have crept up to this much nearer than the
// controller's standstill gap, and still counts as able to stop there.
constexpr double kCreep = 1.5;

// The order key: committed (unable to stop before the next zone ahead) first, then by right of
// way, then by arrival, then by entity index. A vehicle waiting inside a zone for a later one
// is not committed: it holds the zone it is in anyway (ClaimSettler::settle), and those that
// were let go before it keep their turn.
uint64_t order_key(const Approach& a) {
  bool committed = false;
  for (uint32_t k = 0; k < a.count; ++k) {
    if (a.claims[k].to_enter > 0.0) {
      committed = !can_stop(a.claims[k].to_enter, a.stopping);
      break;
    }
  }
  const uint64_t arrived =
      static_cast<uint64_t>(std::max<int64_t>(a.arrived, 0)) & ((uint64_t{1} << 60) - 1);
  return (uint64_t{committed ? 0u : 1u} << 63) | (uint64_t{static_cast<uint8_t>(a.right)} << 61) |
         arrived;
}

}  // namespace

// Told to stop, the controller may run past its standstill gap by up to kCreep short of it; by
// less the slower the vehicle arrives (one crawling up to its stop point stops about where it
// is), so the margin grows with the stopping distance: a vehicle crawling up to its stop point
// still counts as able to stop, and is not let into a zone another holds.
bool can_stop(double to_enter, double stopping) {
  return to_enter - kStopMargin - std::min(kStandstill - kCreep, stopping) >= stopping;
}

void ClaimSettler::settle(std::span<const Approach> approaches, std::span<const uint32_t> who,
                          size_t conflict_count, std::span<YieldPoint> yields) {
  if (held_stamp_.size() < conflict_count) {
    held_stamp_.assign(conflict_count, 0);
    held_side_.assign(conflict_count, 0);
  }
  if (++stamp_ == 0) {  // wrapped: forget every old stamp
    std::fill(held_stamp_.begin(), held_stamp_.end(), 0);
    stamp_ = 1;
  }
  // The zones a vehicle is in, or can no longer stop before even at its maximum deceleration,
  // are its own, whatever the order: another that can still stop waits for it, even if it comes
  // earlier in the order (of two committed to different zones, neither is given the other's).
  const auto take = [&](const Claim& c) {
    if (held_stamp_[c.conflict] != stamp_) {
      held_stamp_[c.conflict] = stamp_;
      held_side_[c.conflict] = c.side;
    }
  };
  order_.clear();
  for (const uint32_t i : who) {
    const Approach& a = approaches[i];
    for (uint32_t k = 0; k < a.count && !can_stop(a.claims[k].to_enter, a.emergency); ++k) {
      take(a.claims[k]);
    }
    order_.emplace_back(order_key(a), i);
  }
  std::sort(order_.begin(), order_.end());
  for (const auto& entry : order_) {
    const uint32_t i = entry.second;
    const Approach& a = approaches[i];
    // The first zone whose other side an earlier vehicle holds, if it can still stop before it,
    // firmly or else at its maximum deceleration (one that cannot goes on: stopping in the zone
    // would help nobody).
    double limit = std::numeric_limits<double>::infinity();
    YieldPoint stop;
    for (uint32_t k = 0; k < a.count; ++k) {
      const Claim& c = a.claims[k];
      if (held_stamp_[c.conflict] == stamp_ && held_side_[c.conflict] != c.side &&
          can_stop(c.to_enter, a.emergency)) {
        limit = c.to_enter;
        stop = YieldPoint{c.node, c.s_enter, !can_stop(c.to_enter, a.stopping)};
        break;
      }
    }
    // It takes the zones it enters before it stops (or all of them).
    for (uint32_t k = 0; k < a.count && a.claims[k].to_enter < limit; ++k) {
      take(a.claims[k]);
    }
    yields[i] = stop;
  }
}

[[gnu::hot]] uint32_t collect_claims(const JunctionConflicts& conflicts, const LanePath& path,
                                     double front, double rear, double speed, Approach& out) {
  const double v = std::max(speed, 0.0);
  const double horizon = kHorizonBase + v * v / (2.0 * kComfort);
  uint32_t count = 0;
  for (size_t p = 0; p < path.count && count < kMaxClaims; ++p) {
    const PathPiece& piece = path.pieces[p];
    if (piece.distance - front > horizon) {
      break;
    }
    const auto zones = conflicts.zones(piece.node);
    const uint32_t first = count;
    for (size_t z = 0; z < zones.size() && count < kMaxClaims; ++z) {
      // In the direction of travel: by s_min going +s, by s_max (about) going -s.
      const ConflictZone& zone = zones[piece.dir > 0 ? z : zones.size() - 1 - z];
      const double enter_s = piece.dir > 0 ? zone.s_min : zone.s_max;
      const double leave_s = piece.dir > 0 ? zone.s_max : zone.s_min;
      const double enter = piece.distance + (enter_s - piece.s_entry) * piece.dir;
      const double leave = piece.distance + (leave_s - piece.s_entry) * piece.dir;
      if (leave < rear - kCleared) {
        continue;  // its rear has left it
      }
      if (enter - front > horizon) {
        // Going +s the zones come by s_min, where they are entered: none after is nearer. Going
        // -s they are entered at s_max, and a zone may lie within a longer one (a merge's runs
        // to the lane's end): one later in the list may still be nearer.
        if (piece.dir > 0) {
          break;
        }
        continue;
      }
      out.claims[count++] = Claim{zone.conflict, zone.side, enter - front, piece.node, enter_s};
    }
    // In path order, by where the path enters them (the settling pass relies on it): an
    // insertion sort, stable, of the few claims of this lane (no buffer to allocate).
    for (uint32_t k = first + 1; k < count; ++k) {
      const Claim claim = out.claims[k];
      uint32_t at = k;
      for (; at > first && claim.to_enter < out.claims[at - 1].to_enter; --at) {
        out.claims[at] = out.claims[at - 1];
      }
      out.claims[at] = claim;
    }
  }
  if (count > 0) {
    out.right = conflicts.right_of_way(out.claims[0].node);
  }
  return count;
}

double gap_to_yield_point(const LanePath& path, const YieldPoint& point, double front) {
  for (size_t p = 0; p < path.count; ++p) {
    const PathPiece& piece = path.pieces[p];
    if (piece.node != point.node) {
      continue;
    }
    const double gap = piece.distance + (point.s - piece.s_entry) * piece.dir - front - kStopMargin;
    // Already past it (it was told to stop when it could no longer): nothing to stop for.
    return gap < -kStopMargin ? std::numeric_limits<double>::infinity() : std::max(gap, 0.0);
  }
  return std::numeric_limits<double>::infinity();
}

void GiveWay::start(const SimState& state) {
  // `--npc` places its vehicles before the first step (traffic/npc_traffic.cpp, place_npcs).
  for (const auto& generator : state.traffic.generators) {
    if (const auto* npcs = dynamic_cast<const NpcPlacement*>(generator.get())) {
      npc_vehicles_ = npcs->vehicle_flags();
      conflicts_ = npcs->conflicts();
    }
  }
  if (!conflicts_) {
    conflicts_ = std::make_shared<const JunctionConflicts>(JunctionConflicts::build(*state.map));
  }
}

[[gnu::hot]] void GiveWay::begin_step(const SimState& state) {
  if (!conflicts_) {
    start(state);
  }
  const size_t count = state.world.entities.size();
  if (approaches_.size() < count) {
    approaches_.resize(count);
    approaching_.resize(count, 0);
    yields_.resize(count);
  }
  for (const uint32_t i : stopped_) {
    yields_[i] = YieldPoint{};
  }
  stopped_.clear();
  who_.clear();
  for (uint32_t i = 0; i < count; ++i) {
    if (approaching_[i] != 0 && state.world.entities[i].state().placed) {
      who_.push_back(i);
    }
  }
  if (who_.empty()) {
    return;
  }
  settler_.settle(approaches_, who_, conflicts_->conflict_count(), yields_);
  for (const uint32_t i : who_) {
    if (yields_[i].node != xodr::kNoLane) {
      stopped_.push_back(i);
    }
  }
}

[[gnu::hot]] void GiveWay::record(uint32_t index, const Entity& me, const LanePath& path,
                                  int64_t tick) {
  Approach& a = approaches_[index];
  const bool was = approaching_[index] != 0;
  const double front = me.info.box.center_x + 0.5 * me.info.box.length;
  const double rear = me.info.box.center_x - 0.5 * me.info.box.length;
  const uint32_t count = collect_claims(*conflicts_, path, front, rear, me.state().speed, a);
  if (count == 0 && !was) {
    return;  // far from every zone, as before: nothing written
  }
  const double v = std::max(me.state().speed, 0.0);
  a.count = count;
  a.stopping = v * v / (2.0 * kFirm);
  a.emergency =
      npc_vehicle(index) ? v * v / (2.0 * std::max(kFirm, me.info.max_deceleration)) : a.stopping;
  if (!was) {
    a.arrived = tick;
  }
  approaching_[index] = count > 0 ? 1 : 0;
}

}  // namespace corsa::engine::detail
