#pragma once

// The sweep and prune of the contacts (state/world_contacts.cpp): the boxes' items in the
// sweep, the sweep from one item, the sort that starts from the last sweep's order, and the
// strips across the sweep's axis that many boxes are swept in.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "state/world_contacts.h"

namespace corsa::engine::detail::sweep_and_prune {

// For world_contacts.cpp alone, with internal linkage as when they were in its unnamed
// namespace: GCC then inlines them as it did there (with external linkage the contacts'
// update ran 0.27 M instructions more at 100 vehicles, callgrind on corsa_bench_traffic).
namespace {

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

}  // namespace

}  // namespace corsa::engine::detail::sweep_and_prune
