#pragma once

// Disjoint sets over 0..n-1 (path halving), used to group links into roads and road ends into
// direct junctions. The smallest index is always the root, so groups come out the same however
// the unions were ordered: deterministic output.

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace corsa::ngii::detail {

class UnionFind {
 public:
  explicit UnionFind(size_t n = 0) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), size_t{0});
  }
  size_t size() const { return parent_.size(); }
  size_t find(size_t x) {
    while (parent_[x] != x) {
      x = parent_[x] = parent_[parent_[x]];
    }
    return x;
  }
  void unite(size_t a, size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) {
      parent_[std::max(a, b)] = std::min(a, b);
    }
  }

 private:
  std::vector<size_t> parent_;
};

}  // namespace corsa::ngii::detail
