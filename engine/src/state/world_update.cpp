#include "state/world_update.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "corsa/engine/oriented_box.h"
#include "corsa/xodr/map.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// The entities whose boxes are not where they were at the last update (moved, appeared, left
// or changed size), into `moved`; records the boxes of now. Returns false when the entities
// are not those of the last update (added or removed): then every box counts as changed.
bool find_moved_boxes(SimState& state, std::vector<uint32_t>& moved) {
  auto& inputs = state.contacts.inputs;
  const auto& entities = state.world.entities;
  moved.clear();
  const bool same_entities = inputs.size() == entities.size();
  inputs.resize(entities.size());
  for (uint32_t i = 0; i < entities.size(); ++i) {
    if (!same_entities || !inputs[i].same_as(entities[i])) {
      moved.push_back(i);
      inputs[i] = {entities[i].state.placed, entities[i].state.pose, entities[i].info.box};
    }
  }
  return same_entities;
}

// Whether the entity's box takes part in the contacts.
bool boxed(const Entity& entity) {
  return entity.state.placed && entity.info.box.length > 0.0 && !entity.ghost;
}

// A box in the sweep; the boxes themselves stay apart (`boxes`, by entity), so that sorting
// moves 40 bytes an item instead of 112.
struct Item {
  double low, high;    ///< extent along x
  double ylow, yhigh;  ///< extent along y
  uint32_t index;      ///< entity
  uint32_t strip;      ///< the first strip across the sweep that holds it (ContactStrips)
};

// Margin (m) by which the y extents are widened before pairs are rejected on them: a pair whose
// boxes the exact test finds overlapping is never rejected for rounding in the extents.
double margin(double v) { return 1e-6 + 1e-12 * std::abs(v); }

bool sweep_order(const Item& a, const Item& b) {
  return a.low < b.low || (a.low == b.low && a.index < b.index);
}

bool y_apart(const Item& a, const Item& b) {
  return b.ylow > a.yhigh + margin(a.yhigh) || a.ylow > b.yhigh + margin(b.yhigh);
}

// !y_apart(a, b) for finite extents, without a branch: most pairs a sweep meets are apart, some
// not, in no pattern a predictor learns (the compiler makes branches of the two comparisons
// however they are combined). For finite u and v, u - v <= 0 exactly when u <= v (a difference
// rounds to 0 only for equal values), so the greater of the two differences is at most 0
// exactly when neither comparison of y_apart holds.
bool y_near_finite(const Item& a, const Item& b) {
  return std::max(b.ylow - (a.yhigh + margin(a.yhigh)), a.ylow - (b.yhigh + margin(b.yhigh))) <=
         0.0;
}

// Calls test(b) for each item b = at(j) after `a` = at(i), j = i + 1 ... size - 1 (sorted for a
// sweep), until ends(b) (true from some item on), whose pair with a is near(b): the items are
// gathered by a pass without a branch per pair (each position written, the count moved by
// near), then tested, in the order of the sweep.
template <typename At, typename Ends, typename Near, typename Test>
void sweep_from(At at, size_t size, size_t i, Ends ends, Near near, Test test) {
  constexpr size_t kBuffer = 64;
  uint32_t kept[kBuffer];
  size_t count = 0;
  for (size_t j = i + 1; j < size && !ends(at(j)); ++j) {
    kept[count] = static_cast<uint32_t>(j);
    count += static_cast<size_t>(near(at(j)));
    if (count == kBuffer) {
      for (size_t k = 0; k < count; ++k) test(at(kept[k]));
      count = 0;
    }
  }
  for (size_t k = 0; k < count; ++k) test(at(kept[k]));
}

// Item j of the items at `data` (for sweep_from over all items; a pointer, which the tests'
// records cannot move, where a vector's would be read again after each).
struct ItemAt {
  const Item* data;
  const Item& operator()(size_t j) const { return data[j]; }
};

// Sorts `items` by `less` (a strict total order), starting from the order of the last sweep
// (`order`, entity indices) when it ran along the same axis: boxes move little in a step, so
// the items are then nearly sorted and an insertion sort takes about one pass. The order is
// unique, so the result is std::sort's. `order` is updated.
template <typename Less>
void sort_from_last(std::vector<Item>& items, std::vector<uint32_t>& order, bool same_axis,
                    size_t entity_count, Less less) {
  if (same_axis && !order.empty()) {
    std::vector<uint32_t> slot(entity_count, UINT32_MAX);
    for (uint32_t k = 0; k < items.size(); ++k) slot[items[k].index] = k;
    std::vector<Item> arranged;
    arranged.reserve(items.size());
    for (const uint32_t entity : order) {
      if (entity < entity_count && slot[entity] != UINT32_MAX) {
        arranged.push_back(items[slot[entity]]);
        slot[entity] = UINT32_MAX;
      }
    }
    for (const Item& item : items) {
      if (slot[item.index] != UINT32_MAX) arranged.push_back(item);  // new since the last sweep
    }
    items.swap(arranged);
    // Insertion sort, given up for std::sort when the order has changed much.
    size_t budget = 8 * items.size() + 64;
    for (size_t k = 1; k < items.size() && budget > 0; ++k) {
      const Item item = items[k];
      size_t j = k;
      for (; j > 0 && less(item, items[j - 1]) && budget > 0; --j, --budget) {
        items[j] = items[j - 1];
      }
      items[j] = item;
    }
    if (budget == 0) std::sort(items.begin(), items.end(), less);
  } else {
    std::sort(items.begin(), items.end(), less);
  }
  order.resize(items.size());
  for (size_t k = 0; k < items.size(); ++k) order[k] = items[k].index;
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
  return std::none_of(entities.begin(), entities.end(), [](const Entity& entity) {
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
    boxes[i] = box_of(entities[i].info.box, entities[i].state.pose);
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

// The spread of every boxed entity's extents as `sweep` keeps them.
ContactSpread kept_spread(const std::vector<Entity>& entities, const ContactSweep& sweep) {
  ContactSpread spread;
  for (uint32_t i = 0; i < entities.size(); ++i) {
    if (boxed(entities[i])) {
      spread.add(sweep.x_extent[i], sweep.y_extent[i]);
    }
  }
  return spread;
}

// Appends to `now` the pairs of moved box `m` with every other boxed entity that the sweep
// would record: the same filters (the x extents in the sweep's order, `y_near_finite`) and the
// exact test of the pair in the order the sweep along its axis meets them. A pair of two moved
// boxes is tested once, from the lower index.
void add_moved_box_pairs(const SimState& state, const ContactSweep& sweep, uint32_t m, bool along_y,
                         std::vector<std::pair<uint32_t, uint32_t>>& now) {
  const auto& entities = state.world.entities;
  const std::vector<OrientedBox>& boxes = state.contacts.boxes;
  const Item p = sweep_item(sweep, m);
  for (uint32_t j = 0; j < entities.size(); ++j) {
    if (j == m || !boxed(entities[j]) || (sweep.moved_mark[j] != 0 && j < m)) {
      continue;
    }
    const Item q = sweep_item(sweep, j);
    const bool p_first = sweep_order(p, q);
    const Item& first = p_first ? p : q;
    const Item& second = p_first ? q : p;
    if (!(second.low <= first.high) || !y_near_finite(p, q)) {
      continue;
    }
    // The sweep tests the pair from the earlier of the two along its axis.
    const bool p_leads =
        along_y ? (p.ylow < q.ylow || (p.ylow == q.ylow && p.index < q.index)) : p_first;
    const bool touching =
        p_leads ? overlap(boxes[p.index], boxes[q.index]) : overlap(boxes[q.index], boxes[p.index]);
    if (touching) {
      now.emplace_back(std::min(m, j), std::max(m, j));
    }
  }
}

// The contacts when only the boxes in `sweep.moved` changed since a complete update: the pairs
// of two unmoved boxes are the last update's (neither box changed), and each moved box is
// tested against every other box under the sweep's own filters, so that a pair is tested
// exactly when the sweep would test it, in the sweep's order of the two (the axis chosen as the
// sweep chooses it): the same pairs as a sweep over all boxes. Returns false, having changed
// no pair, when it does not apply (moved_update_applies) or a moved box's extents are not
// finite (no total order for the sweep's filters).
bool update_moved_contacts(SimState& state, ContactSweep& sweep) {
  if (!moved_update_applies(state, sweep) || !refresh_moved_boxes(state, sweep)) {
    return false;
  }
  const auto& entities = state.world.entities;
  const bool along_y = kept_spread(entities, sweep).along_y();
  sweep.moved_mark.assign(entities.size(), 0);
  for (const uint32_t i : sweep.moved) {
    sweep.moved_mark[i] = 1;
  }
  std::vector<std::pair<uint32_t, uint32_t>> previous;
  previous.swap(state.contacts.pairs);
  auto& now = state.contacts.pairs;
  for (const auto& pair : previous) {
    if (sweep.moved_mark[pair.first] == 0 && sweep.moved_mark[pair.second] == 0) {
      now.push_back(pair);
    }
  }
  for (const uint32_t m : sweep.moved) {
    if (boxed(entities[m])) {
      add_moved_box_pairs(state, sweep, m, along_y, now);
    }
  }
  std::sort(now.begin(), now.end());
  record_new_contacts(state, now, previous);
  return true;
}

// Makes every boxed entity's box and its extents along x and y. Each box depends only on its
// entity: made on several threads when the sweep may share them out, so the result is the same
// on any number.
void make_all_boxes(SimState& state, ContactSweep& sweep) {
  const auto& entities = state.world.entities;
  std::vector<OrientedBox>& boxes = state.contacts.boxes;
  boxes.resize(entities.size());
  sweep.x_extent.resize(entities.size());
  sweep.y_extent.resize(entities.size());
  const auto make_boxes = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (!boxed(entities[i])) {
        continue;
      }
      boxes[i] = box_of(entities[i].info.box, entities[i].state.pose);
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

// Strips across the sweep's axis (along x for a sweep along y, and the other way round), of equal
// width: a box goes into every strip its extent across covers, and each strip is swept on its
// own, so that a box meets the boxes of its stretch of the axis in its strips only, not those
// of the whole map's width (with many vehicles spread over a city, the one sweep met about as
// many boxes per box as there were boxes per stripe of the map, a number that grows with the
// vehicles). A pair is tested in one strip only: the one that holds the greater of the two
// lows across, which both boxes' extents cover when the pair is near across.
struct ContactStrips {
  double origin = 0.0;     ///< m, where strip 0 begins
  double per_metre = 1.0;  ///< strips per metre (1 / their width)
  uint32_t count = 1;

  /// The strip holding coordinate v (the first or the last beyond them): non-decreasing in v
  /// (each operation rounds monotonically).
  uint32_t of(double v) const {
    const double k = std::min((v - origin) * per_metre, count - 1.0);
    return k > 0.0 ? static_cast<uint32_t>(k) : 0u;
  }
};

// Strips over [low, high] (m) across the sweep for `boxes` boxes spread over `along` (m) along
// it: about kBoxesPerStrip boxes each, none narrower than kStripWidth. One strip (the one sweep)
// unless the one sweep would meet kMeetings boxes or more per box (about a car's length of the
// axis' share of the boxes): below that, sharing the boxes out costs more than the sweep's
// pairs (callgrind on Town04: at 100 cars, half a box met per box, the strips cost 13% more
// than the one sweep; at 800 cars, four, 7% less).
ContactStrips choose_strips(double low, double high, double along, size_t boxes) {
  constexpr size_t kBoxesPerStrip = 16;
  constexpr double kStripWidth = 16.0;  // m: three car lengths, so few boxes lie in two strips
  constexpr double kMaxStrips = 4096.0;
  constexpr double kCarLength = 5.0;  // m
  constexpr double kMeetings = 2.0;
  ContactStrips strips;
  strips.origin = low;
  const double span = high - low;
  const double wanted = static_cast<double>(boxes / kBoxesPerStrip);  // whole strips
  if (!(static_cast<double>(boxes) * kCarLength >= kMeetings * along) || wanted < 2.0 ||
      !(span > 2.0 * kStripWidth)) {
    return strips;
  }
  const double width = std::max(span / wanted, kStripWidth);
  strips.count = static_cast<uint32_t>(std::clamp(std::ceil(span / width), 1.0, kMaxStrips));
  strips.per_metre = 1.0 / width;
  return strips;
}

// Sweeps `items` (sorted for the sweep) strip by strip: each item is copied into every strip
// from strips.of(low(item)) to strips.of(high(item)), in the sweep's order, with its first
// strip; then each strip's items are swept, and a pair near(p, q) (which implies that the two
// extents across overlap, within high's margin) is tested only in the later first strip of the
// two. The pairs tested, and the order of the two in each test, are those of one sweep over
// all items.
// The strips' members are positions in `items` (4 bytes each instead of a 40-byte copy, in
// storage kept from one sweep to the next: the copies' fresh memory cost more cache misses
// than the pairs they spared).
template <typename Low, typename High, typename Ends, typename Near, typename Test>
void sweep_strips(std::vector<Item>& items, ContactSweep& sweep, const ContactStrips& strips,
                  Low low, High high, Ends ends, Near near, Test test) {
  std::vector<uint32_t>& start = sweep.strip_start;
  std::vector<uint32_t>& last = sweep.strip_last;
  std::vector<uint32_t>& members = sweep.strip_members;
  start.assign(strips.count + 1, 0);
  last.resize(items.size());
  for (size_t k = 0; k < items.size(); ++k) {
    Item& item = items[k];
    item.strip = strips.of(low(item));
    last[k] = strips.of(high(item));
    for (uint32_t s = item.strip; s <= last[k]; ++s) ++start[s + 1];
  }
  for (uint32_t k = 0; k < strips.count; ++k) start[k + 1] += start[k];
  members.resize(start.back());
  for (size_t k = 0; k < items.size(); ++k) {
    for (uint32_t s = items[k].strip; s <= last[k]; ++s) {
      members[start[s]++] = static_cast<uint32_t>(k);
    }
  }
  // Each start was moved to the next strip's: strip k's members are [k ? start[k - 1] : 0,
  // start[k]).
  uint32_t begin = 0;
  for (uint32_t k = 0; k < strips.count; ++k) {
    const uint32_t* strip = members.data() + begin;
    const size_t size = start[k] - begin;
    begin = start[k];
    const Item* data = items.data();
    const auto at = [data, strip](size_t j) -> const Item& { return data[strip[j]]; };
    for (size_t a = 0; a < size; ++a) {
      const Item& p = at(a);
      sweep_from(
          at, size, a, [&](const Item& q) { return ends(p, q); },
          [&](const Item& q) { return near(p, q) & (std::max(p.strip, q.strip) == k); },
          [&](const Item& q) { test(p, q); });
    }
  }
}

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
  for (size_t a = 0; a < items.size(); ++a) {
    const Item& p = items[a];
    sweep_from(
        ItemAt{items.data()}, items.size(), a, [&](const Item& q) { return ends(p, q); },
        [&](const Item& q) { return near(p, q); }, [&](const Item& q) { test(p, q); });
  }
}

// Sweeps along x; pairs apart along y (with a rounding margin) cannot overlap and are skipped.
// Extents that are not all `finite` (NaN or infinite) have no total order to start from; finite
// ones many boxes sweep in strips along y.
void sweep_along_x(std::vector<Item>& items, ContactSweep& sweep, size_t entity_count,
                   const ContactSpread& spread, const std::vector<OrientedBox>& boxes,
                   ContactRecorder& record) {
  const bool finite = spread.finite;
  if (finite) {
    sort_from_last(items, sweep.order, !sweep.along_y, entity_count, sweep_order);
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
  for (size_t a = 0; a < items.size(); ++a) {
    const Item& p = items[a];
    const auto ends_p = [&](const Item& q) { return ends(p, q); };
    const auto test_p = [&](const Item& q) { test(p, q); };
    if (finite) {
      sweep_from(
          ItemAt{items.data()}, items.size(), a, ends_p,
          [&](const Item& q) { return y_near_finite(p, q); }, test_p);
    } else {
      sweep_from(
          ItemAt{items.data()}, items.size(), a, ends_p,
          [&](const Item& q) { return !y_apart(p, q); }, test_p);
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

}  // namespace

void update_contacts(SimState& state, ContactSweep& sweep) {
  // Nothing moved, appeared or left: the contacts are those of the last update, and none is new.
  const bool same_entities = find_moved_boxes(state, sweep.moved);
  if (sweep.moved.empty()) {
    return;
  }
  if (same_entities && update_moved_contacts(state, sweep)) {
    return;
  }
  auto& entities = state.world.entities;
  std::vector<std::pair<uint32_t, uint32_t>> previous;
  previous.swap(state.contacts.pairs);
  // Boxes whose extents overlap along the sweep's axis (sweep and prune) are tested exactly.
  make_all_boxes(state, sweep);
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
}

namespace {

// Off the road: on no lane, or on a lane of type none. OpenDRIVE 1.8 §9.5.3: a lane of type none
// "describes the space on the outermost edge of the road and does not have actual content. Its
// only purpose is for applications to register that ASAM OpenDRIVE is still present in case the
// (human) driver leaves the road". esmini's OffroadCondition counts it off the road too (the road
// width without such lanes).
bool off_road(const SimState& state, const Entity& entity) {
  if (!entity.state.road) return true;
  if (state.map == nullptr || entity.state.road->lane == 0) return false;
  const RoadCoordinates& at = *entity.state.road;
  const LaneFollow& follow = entity.lane;
  if (follow.node != xodr::kNoLane && follow.road == at.road && follow.section == at.section &&
      follow.lane == at.lane) {
    // The lane it follows (nearly always): its type from the lane graph's node, one read
    // instead of a search through the road's lanes every step.
    return state.map->lane_graph().info(follow.node).type == xodr::LaneType::kNone;
  }
  const xodr::Lane* lane = state.map->lane(xodr::LaneRef{at.road, at.section, at.lane});
  return lane != nullptr && lane->type == xodr::LaneType::kNone;
}

// Below this speed (m/s) an entity stands still. StandStillCondition (1.3): true "if the
// triggering entity/entities stands still for a given amount of time"; the text names no speed,
// and an entity slowed by a controller or a relative target only nears 0. esmini's threshold
// (ScenarioEngine.cpp STAND_STILL_THRESHOLD, -1e-3 < v < 1e-3), taken under both readings, as
// every reading the standard leaves open.
constexpr double kStandStillSpeed = 1e-3;

}  // namespace

void update_timers(SimState& state, bool advance) {
  const double dt = advance ? state.time.dt() : 0.0;
  for (Entity& entity : state.world.entities) {
    // Each timer counts the time since its condition began: 0 at the first tick it holds.
    const bool was_still = entity.standing_still;
    entity.standing_still = std::abs(entity.state.speed) < kStandStillSpeed;
    entity.standstill_time =
        entity.standing_still ? (was_still ? entity.standstill_time + dt : 0.0) : 0.0;
    const bool offroad = off_road(state, entity);
    entity.offroad_time = offroad ? (entity.was_offroad ? entity.offroad_time + dt : 0.0) : 0.0;
    entity.was_offroad = offroad;
    entity.end_of_road_time =
        entity.end_of_road ? (entity.was_at_end ? entity.end_of_road_time + dt : 0.0) : 0.0;
    entity.was_at_end = entity.end_of_road;
  }
}

}  // namespace corsa::engine::detail
