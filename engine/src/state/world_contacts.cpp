#include "state/world_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "corsa/engine/oriented_box.h"
#include "geometry/box_placement.h"
#include "state/contact_sweep.h"
#include "state/sim_state.h"

// The helpers are in sweep_and_prune (state/contact_sweep.h) beside the sweep itself, in an
// unnamed namespace of their own.
namespace corsa::engine::detail::sweep_and_prune {

namespace {

// Whether the entity's box takes part in the contacts.
bool boxed(const Entity& entity) {
  return entity.state().placed && entity.info.box.length > 0.0 && !entity.ghost;
}

// The marks of the moved entities (ContactSweep::moved_mark; 0: not moved): moved, or moved
// keeping its heading to the bit, its box of the last update made then (the entity boxed at
// that update), so that the box of its heading's cosine and sine is made from that box's.
constexpr uint8_t kMoved = 1;
constexpr uint8_t kMovedSameHeading = 2;

// The entities whose boxes are not where they were at the last update (moved, appeared, left
// or changed size), into `sweep.moved`, each marked (`moved_mark`, sized to the entities) when
// the entities are those of the last update; records the boxes of now. Returns false when the
// entities are not those of the last update (added or removed): then every box counts as
// changed, and none is marked.
// An entity found placed and posed as recorded, its state written since (its speed, say), has
// its count of writes taken: while the count stands, the next update compares nothing. (Kept
// at the count of its last move instead, a standing entity whose state had been written once
// was compared every update: in highway_merge_advanced, five of its six entities every step,
// more than the rest of the contacts' update.)
bool find_moved_boxes(SimState& state, ContactSweep& sweep) {
  auto& inputs = state.contacts.inputs;
  const auto& entities = state.world.entities;
  std::vector<uint32_t>& moved = sweep.moved;
  moved.clear();
  // The count and places read once: `moved` grows in memory the compiler cannot tell apart from
  // the entities' and inputs', which it would otherwise read again after each moved box.
  const size_t count = entities.size();
  const bool same_entities = inputs.size() == count;
  if (!same_entities) {
    inputs.resize(count);
  } else if (sweep.moved_mark.size() != count) {
    sweep.moved_mark.assign(count, 0);
  }
  // The last update's boxes are those of every entity boxed then.
  const bool boxes_kept = same_entities && state.contacts.boxes.size() == count;
  ContactInput* const input = inputs.data();
  const Entity* const entity = entities.data();
  for (uint32_t i = 0; i < count; ++i) {
    if (same_entities && input[i].same_as(entity[i])) {
      input[i].changes = entity[i].state_changes();
      continue;
    }
    if (same_entities) {
      const bool same_heading = boxes_kept && input[i].placed && boxed(entity[i]) &&
                                same_bits(input[i].pose.h, entity[i].state().pose.h);
      sweep.moved_mark[i] = same_heading ? kMovedSameHeading : kMoved;
    }
    moved.push_back(i);
    input[i] = ContactInput(entity[i]);
  }
  return same_entities;
}

// Entity `i`'s contact box now, from the cosine and sine of its box of the last update when
// `mark` says it kept its heading (the same box as box_of's).
OrientedBox contact_box(const Entity& entity, uint8_t mark, const OrientedBox& last) {
  return mark == kMovedSameHeading
             ? box_at_heading(entity.info.box, entity.state().pose, last.cos_h, last.sin_h)
             : box_of(entity.info.box, entity.state().pose);
}

// Records the pairs of `now` (sorted) that `previous` (sorted) does not hold as collisions
// begun at this tick, in entity order.
void record_new_contacts(SimState& state, const std::vector<std::pair<uint32_t, uint32_t>>& now,
                         const std::vector<std::pair<uint32_t, uint32_t>>& previous) {
  for (const auto& pair : now) {
    if (!std::binary_search(previous.begin(), previous.end(), pair)) {
      state.collisions.push_back({state.tick, state.now(), pair.first, pair.second});
    }
  }
}

// Moves the last update's pairs to `sweep.previous` and empties the pairs for the new ones,
// keeping the storage of both.
const std::vector<std::pair<uint32_t, uint32_t>>& take_previous_pairs(SimState& state,
                                                                      ContactSweep& sweep) {
  sweep.previous.swap(state.contacts.pairs);
  state.contacts.pairs.clear();
  return sweep.previous;
}

// The bounds of the boxed entities' extents, and whether every extent is finite.
struct ContactSpread {
  bool any = false;
  bool finite = true;
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;

  void add(const Interval& x, const Interval& y) {
    finite = finite && std::isfinite(x.low) && std::isfinite(x.high) && std::isfinite(y.low) &&
             std::isfinite(y.high);
    x0 = any ? std::min(x0, x.low) : x.low;
    x1 = any ? std::max(x1, x.high) : x.high;
    y0 = any ? std::min(y0, y.low) : y.low;
    y1 = any ? std::max(y1, y.high) : y.high;
    any = true;
  }
  /// Spread more along y (a road running north): the sweep then runs along y.
  bool along_y() const { return y1 - y0 > x1 - x0; }
};

// Entity `i`'s box in the sweep, from the extents kept in `sweep`.
Item sweep_item(const ContactSweep& sweep, uint32_t i) {
  return Item{sweep.x_extent[i].low,
              sweep.x_extent[i].high,
              sweep.y_extent[i].low,
              sweep.y_extent[i].high,
              i,
              0};
}

// Whether the update of the moved boxes alone applies: the last update was complete and
// covered these entities, few enough boxes moved that testing each against every other box is
// cheaper than a sweep, and no trailer is coupled (or was, and may still touch its tower).
bool moved_update_applies(const SimState& state, const ContactSweep& sweep) {
  const auto& entities = state.world.entities;
  const size_t count = entities.size();
  // A moved box costs a test of every other box; a sweep costs about a box's making per box.
  constexpr size_t kMovedAlways = 16;
  constexpr size_t kBoxesPerMovedBox = 32;
  if (!sweep.complete || state.contacts.boxes.size() != count || sweep.x_extent.size() != count ||
      (sweep.moved.size() > kMovedAlways && sweep.moved.size() * kBoxesPerMovedBox > count)) {
    return false;
  }
  // Only a connection sets any of the links (motion/trailers.h).
  return !state.trailers_connected ||
         std::none_of(entities.begin(), entities.end(), [](const Entity& entity) {
           return entity.towed_by || entity.towing || entity.unhitched_from;
         });
}

// Makes the boxes and extents of the moved entities again. False when an extent is not finite
// (the sweep's own path then makes every box again).
bool refresh_moved_boxes(SimState& state, ContactSweep& sweep) {
  const auto& entities = state.world.entities;
  std::vector<OrientedBox>& boxes = state.contacts.boxes;
  for (const uint32_t i : sweep.moved) {
    if (!boxed(entities[i])) {
      continue;
    }
    boxes[i] = contact_box(entities[i], sweep.moved_mark[i], boxes[i]);
    const Interval x = project(boxes[i], 1.0, 0.0);
    const Interval y = project(boxes[i], 0.0, 1.0);
    if (!std::isfinite(x.low) || !std::isfinite(x.high) || !std::isfinite(y.low) ||
        !std::isfinite(y.high)) {
      return false;
    }
    sweep.x_extent[i] = x;
    sweep.y_extent[i] = y;
  }
  return true;
}

// Appends to `now` the pairs of moved box `m` with every other boxed entity that the sweep
// would record: the same filters (the x extents, `y_near_finite`) and the exact test. A pair of
// two moved boxes is tested once, from the lower index. The sweep tests a pair from the earlier
// of the two along its axis; overlap() is symmetric (the same four axes and the same
// comparisons of the two projections, whichever box comes first), so the order is not taken.
// The x extents are compared first, from the kept extents alone: most boxes are apart along
// x, and the entity (its box, whether it is boxed) is then not read.
void add_moved_box_pairs(const SimState& state, const ContactSweep& sweep, uint32_t m,
                         std::vector<std::pair<uint32_t, uint32_t>>& now) {
  const auto& entities = state.world.entities;
  const std::vector<OrientedBox>& boxes = state.contacts.boxes;
  const Item p = sweep_item(sweep, m);
  // Read once, as in find_moved_boxes (`now` grows).
  const auto count = static_cast<uint32_t>(entities.size());
  const Interval* const x_extent = sweep.x_extent.data();
  for (uint32_t j = 0; j < count; ++j) {
    // The sweep's x filter: the later of the two in x order starts before the earlier ends. For
    // finite extents (low <= high, as the moved update keeps them) this is the overlap of the
    // two closed intervals, whichever comes first.
    if (!(x_extent[j].low <= p.high && p.low <= x_extent[j].high)) {
      continue;
    }
    if (j == m || !boxed(entities[j]) || (sweep.moved_mark[j] != 0 && j < m)) {
      continue;
    }
    if (y_near_finite(p, sweep_item(sweep, j)) && overlap(boxes[m], boxes[j])) {
      now.emplace_back(std::min(m, j), std::max(m, j));
    }
  }
}

// Into the emptied `now`: the pairs of `previous` (sorted) between two unmoved boxes, merged
// in order with `fresh` (sorted, each with a moved box: no pair is in both).
void merge_kept_pairs(const ContactSweep& sweep,
                      const std::vector<std::pair<uint32_t, uint32_t>>& previous,
                      const std::vector<std::pair<uint32_t, uint32_t>>& fresh,
                      std::vector<std::pair<uint32_t, uint32_t>>& now) {
  size_t k = 0;
  for (const auto& pair : previous) {
    if (sweep.moved_mark[pair.first] != 0 || sweep.moved_mark[pair.second] != 0) {
      continue;
    }
    while (k < fresh.size() && fresh[k] < pair) {
      now.push_back(fresh[k++]);
    }
    now.push_back(pair);
  }
  now.insert(now.end(), fresh.begin() + static_cast<std::ptrdiff_t>(k), fresh.end());
}

// The contacts when only the boxes in `sweep.moved` changed since a complete update: the pairs
// of two unmoved boxes are the last update's (neither box changed), and each moved box is
// tested against every other box under the sweep's own filters, so that a pair is tested
// exactly when the sweep would test it (the exact test gives the same in either order): the
// same pairs as a sweep over all boxes. Only a pair with a moved box can be new: those alone
// are sorted, merged with the kept ones and looked up in the last pairs (the moved boxes are
// marked, find_moved_boxes). Returns false, having
// changed no pair, when it does not apply (moved_update_applies) or a moved box's extents are
// not finite (no total order for the sweep's filters).
bool update_moved_contacts(SimState& state, ContactSweep& sweep) {
  const auto& entities = state.world.entities;
  if (!moved_update_applies(state, sweep) || !refresh_moved_boxes(state, sweep)) {
    return false;
  }
  auto& fresh = sweep.moved_pairs;
  fresh.clear();
  for (const uint32_t m : sweep.moved) {
    if (boxed(entities[m])) {
      add_moved_box_pairs(state, sweep, m, fresh);
    }
  }
  std::sort(fresh.begin(), fresh.end());
  const auto& previous = take_previous_pairs(state, sweep);
  merge_kept_pairs(sweep, previous, fresh, state.contacts.pairs);
  record_new_contacts(state, fresh, previous);
  return true;
}

// Makes every boxed entity's box and its extents along x and y; with `marked` (the entities
// are those of the last update, the moved ones marked), only the moved entities': the others'
// are as the last update made them. Each box depends only on its entity: made on several
// threads when the sweep may share them out, so the result is the same on any number.
void make_all_boxes(SimState& state, ContactSweep& sweep, bool marked) {
  const auto& entities = state.world.entities;
  std::vector<OrientedBox>& boxes = state.contacts.boxes;
  boxes.resize(entities.size());
  sweep.x_extent.resize(entities.size());
  sweep.y_extent.resize(entities.size());
  // Boxes the moves made, where the entity still stands as then (the same value box_of and
  // project give).
  const std::vector<PremadeContactBox>* premade =
      state.contacts.premade_fresh && state.contacts.premade.size() == entities.size()
          ? &state.contacts.premade
          : nullptr;
  const uint8_t* const mark = marked ? sweep.moved_mark.data() : nullptr;
  const auto make_boxes = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if ((mark != nullptr && mark[i] == 0) || !boxed(entities[i])) {
        continue;
      }
      if (premade != nullptr) {
        const PremadeContactBox& made = (*premade)[i];
        if (made.boxed && made.input.same_as(entities[i])) {
          boxes[i] = made.box;
          sweep.x_extent[i] = made.x;
          sweep.y_extent[i] = made.y;
          continue;
        }
      }
      boxes[i] = contact_box(entities[i], mark != nullptr ? mark[i] : kMoved, boxes[i]);
      sweep.x_extent[i] = project(boxes[i], 1.0, 0.0);
      sweep.y_extent[i] = project(boxes[i], 0.0, 1.0);
    }
  };
  if (sweep.share) {
    sweep.share(entities.size(), make_boxes);
  } else {
    make_boxes(0, entities.size());
  }
}

// The sweep's items of the boxed entities, in index order, into `items`; their spread.
ContactSpread gather_items(const std::vector<Entity>& entities, const ContactSweep& sweep,
                           std::vector<Item>& items) {
  ContactSpread spread;
  items.reserve(entities.size());
  for (uint32_t i = 0; i < entities.size(); ++i) {
    if (!boxed(entities[i])) {
      continue;
    }
    const Interval x = sweep.x_extent[i];
    const Interval y = sweep.y_extent[i];
    spread.add(x, y);
    items.push_back({x.low, x.high, y.low, y.high, i, 0});
  }
  return spread;
}

// Where the sweep's overlapping pairs go: a trailer and the vehicle towing it meet at the hitch
// (also for a while after they were disconnected, until they part), which is no collision, so
// such coupled pairs are kept apart (`touching`) from the contacts (`now`).
class ContactRecorder {
 public:
  ContactRecorder(const std::vector<Entity>& entities,
                  std::vector<std::pair<uint32_t, uint32_t>>& now)
      : entities_(entities), now_(now) {}

  void operator()(const Item& p, const Item& q) {
    const Entity& first = entities_[p.index];
    const bool coupled = first.towed_by == q.index || first.towing == q.index ||
                         first.unhitched_from == q.index ||
                         entities_[q.index].unhitched_from == p.index;
    (coupled ? touching_ : now_)
        .emplace_back(std::min(p.index, q.index), std::max(p.index, q.index));
  }
  /// Coupled pairs whose boxes overlap.
  const std::vector<std::pair<uint32_t, uint32_t>>& touching() const { return touching_; }

 private:
  const std::vector<Entity>& entities_;
  std::vector<std::pair<uint32_t, uint32_t>>& now_;
  std::vector<std::pair<uint32_t, uint32_t>> touching_;
};

// Sweeps along y (the boxes spread more that way), testing a pair when the x sweep would have
// (the later of the two in x order starts before the earlier ends), with finite extents; in
// strips along x when there are many boxes.
void sweep_along_y(std::vector<Item>& items, ContactSweep& sweep, size_t entity_count,
                   const ContactSpread& spread, const std::vector<OrientedBox>& boxes,
                   ContactRecorder& record) {
  sort_from_last(items, sweep.order, sweep.along_y, entity_count, [](const Item& a, const Item& b) {
    return a.ylow < b.ylow || (a.ylow == b.ylow && a.index < b.index);
  });
  sweep.along_y = true;
  const auto ends = [](const Item& p, const Item& q) {
    return !(q.ylow <= p.yhigh + margin(p.yhigh));
  };
  const auto near = [](const Item& p, const Item& q) {
    // sweep_order(p, q), and the x extents' test for the pair in that order.
    const bool p_first = (p.low < q.low) | ((p.low == q.low) & (p.index < q.index));
    const double first_high = p_first ? p.high : q.high;
    const double second_low = p_first ? q.low : p.low;
    return (second_low <= first_high) & y_near_finite(p, q);
  };
  const auto test = [&](const Item& p, const Item& q) {
    if (overlap(boxes[p.index], boxes[q.index])) record(p, q);
  };
  const ContactStrips strips =
      choose_strips(spread.x0, spread.x1, spread.y1 - spread.y0, items.size());
  sweep.strips = strips.count;
  if (strips.count > 1) {
    // The x test above holds only for extents that overlap (a low and a high are in order).
    sweep_strips(
        items, sweep, strips, [](const Item& item) { return item.low; },
        [](const Item& item) { return item.high; }, ends, near, test);
    return;
  }
  // The items' place and count read once: `record` writes to memory the compiler cannot tell
  // apart from `items`' own, so items.data() and items.size() would be read again after each
  // pair recorded, and per item.
  const ItemAt at{items.data()};
  const size_t size = items.size();
  for (size_t a = 0; a < size; ++a) {
    const Item& p = at(a);
    sweep_from(
        at, size, a, [&](const Item& q) { return ends(p, q); },
        [&](const Item& q) { return near(p, q); }, [&](const Item& q) { test(p, q); });
  }
}

// Sweeps along x; pairs apart along y (with a rounding margin) cannot overlap and are skipped.
// Extents that are not all `finite` (NaN or infinite) have no total order to start from; finite
// ones many boxes sweep in strips along y.
[[gnu::hot]] void sweep_along_x(std::vector<Item>& items, ContactSweep& sweep, size_t entity_count,
                                const ContactSpread& spread, const std::vector<OrientedBox>& boxes,
                                ContactRecorder& record) {
  const bool finite = spread.finite;
  if (finite) {
    // A lambda, not the function's pointer, so that the insertion sort's comparisons are inlined.
    sort_from_last(items, sweep.order, !sweep.along_y, entity_count,
                   [](const Item& a, const Item& b) { return sweep_order(a, b); });
    sweep.along_y = false;
  } else {
    std::sort(items.begin(), items.end(), sweep_order);
    sweep.order.clear();
  }
  const auto ends = [](const Item& p, const Item& q) { return !(q.low <= p.high); };
  const auto test = [&](const Item& p, const Item& q) {
    if (overlap(boxes[p.index], boxes[q.index])) record(p, q);
  };
  const ContactStrips strips =
      finite ? choose_strips(spread.y0, spread.y1, spread.x1 - spread.x0, items.size())
             : ContactStrips{};
  sweep.strips = strips.count;
  if (strips.count > 1) {
    // y_near_finite(p, q) holds only if each low is at most the other's high plus its margin.
    sweep_strips(
        items, sweep, strips, [](const Item& item) { return item.ylow; },
        [](const Item& item) { return item.yhigh + margin(item.yhigh); }, ends,
        [](const Item& p, const Item& q) { return y_near_finite(p, q); }, test);
    return;
  }
  // Read once, as in sweep_along_y.
  const ItemAt at{items.data()};
  const size_t size = items.size();
  for (size_t a = 0; a < size; ++a) {
    const Item& p = at(a);
    const auto ends_p = [&](const Item& q) { return ends(p, q); };
    const auto test_p = [&](const Item& q) { test(p, q); };
    if (finite) {
      sweep_from(
          at, size, a, ends_p, [&](const Item& q) { return y_near_finite(p, q); }, test_p);
    } else {
      sweep_from(
          at, size, a, ends_p, [&](const Item& q) { return !y_apart(p, q); }, test_p);
    }
  }
}

// A disconnected trailer that no longer touches its former tower can collide with it again.
void release_parted_trailers(std::vector<Entity>& entities,
                             const std::vector<std::pair<uint32_t, uint32_t>>& touching) {
  for (uint32_t i = 0; i < entities.size(); ++i) {
    const auto other = entities[i].unhitched_from;
    if (!other) continue;
    const bool still = std::any_of(touching.begin(), touching.end(), [&](const auto& pair) {
      return (pair.first == i && pair.second == *other) ||
             (pair.first == *other && pair.second == i);
    });
    if (!still) entities[i].unhitched_from.reset();
  }
}

// Every boxed entity's box swept, the moved ones' made again (every one's when `marked` is
// false: entities appeared or left): when the update of the moved boxes does not apply. Out of
// line, so that the contacts' per-step code (mostly the moved boxes' update) stays small.
[[gnu::noinline]] void sweep_all_contacts(SimState& state, ContactSweep& sweep, bool marked) {
  auto& entities = state.world.entities;
  const auto& previous = take_previous_pairs(state, sweep);
  // Boxes whose extents overlap along the sweep's axis (sweep and prune) are tested exactly.
  make_all_boxes(state, sweep, marked);
  std::vector<Item> items;
  const ContactSpread spread = gather_items(entities, sweep, items);
  auto& now = state.contacts.pairs;
  ContactRecorder record(entities, now);
  if (spread.finite && spread.along_y()) {
    sweep_along_y(items, sweep, entities.size(), spread, state.contacts.boxes, record);
  } else {
    sweep_along_x(items, sweep, entities.size(), spread, state.contacts.boxes, record);
  }
  release_parted_trailers(entities, record.touching());
  // Entity order, independent of the sweep order; new contacts are recorded in that order.
  std::sort(now.begin(), now.end());
  record_new_contacts(state, now, previous);
  sweep.complete = spread.finite;
  state.contacts.premade_fresh = false;
}

}  // namespace

}  // namespace corsa::engine::detail::sweep_and_prune

namespace corsa::engine::detail {

void premake_contact_box(SimState& state, uint32_t i) {
  using namespace sweep_and_prune;
  const Entity& entity = state.world.entities[i];
  PremadeContactBox& made = state.contacts.premade[i];
  made.boxed = boxed(entity);
  if (!made.boxed) {
    return;
  }
  made.input = ContactInput(entity);
  made.box = box_of(entity.info.box, entity.state().pose);
  made.x = project(made.box, 1.0, 0.0);
  made.y = project(made.box, 0.0, 1.0);
}

[[gnu::hot]] void update_contacts(SimState& state, ContactSweep& sweep) {
  using namespace sweep_and_prune;
  // Nothing moved, appeared or left: the contacts are those of the last update, and none is new.
  const bool same_entities = find_moved_boxes(state, sweep);
  if (sweep.moved.empty()) {
    state.contacts.premade_fresh = false;
    return;
  }
  if (same_entities && update_moved_contacts(state, sweep)) {
    state.contacts.premade_fresh = false;
  } else {
    sweep_all_contacts(state, sweep, same_entities);
  }
  // The marks (find_moved_boxes) cleared, not every entity's set again.
  if (same_entities) {
    for (const uint32_t i : sweep.moved) {
      sweep.moved_mark[i] = 0;
    }
  }
}

}  // namespace corsa::engine::detail
