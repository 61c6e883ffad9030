#pragma once

// The two real areas converted once per test binary (each conversion takes a fraction of a
// second, many test cases look at the result).

#include <map>
#include <string>

#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "ngii_fixtures.h"

namespace corsa::test {

struct ConvertedArea {
  ngii::Layers layers;
  ngii::Conversion conversion;
  Diagnostics diagnostics;
  xodr::Map map;
};

/// Converted area by folder name ("kcity", "seoul_sangam_testbed"), built on first use.
inline const ConvertedArea& converted(const std::string& name) {
  static std::map<std::string, std::unique_ptr<ConvertedArea>> cache;
  auto& slot = cache[name];
  if (!slot) {
    auto diagnostics = std::make_unique<Diagnostics>();
    ngii::Layers layers = ngii::read_layers(ngii_area(name), *diagnostics);
    ngii::Conversion conversion = ngii::convert(layers, {}, *diagnostics);
    xodr::Map map = xodr::Map::build(conversion.map, *diagnostics);
    slot.reset(new ConvertedArea{std::move(layers), std::move(conversion), {}, std::move(map)});
    for (const auto& d : diagnostics->all()) {
      slot->diagnostics.add(d);
    }
  }
  return *slot;
}

}  // namespace corsa::test
