// Small synthetic NGII layers for the junction-mouth tests (mouths_*_test.cpp) and the gap
// measure run on their conversion: where lanes join, no wedge or sliver of unpaved ground lies
// between them (mouth_gaps.h).

#pragma once

#include <catch2/catch.hpp>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "mouth_gaps.h"
#include "synthetic_layers.h"

namespace corsa::ngii::testing {

/// Layers placed in metres around a projected origin (x 300,000 m, y 4,100,000 m) at 50 m height.
struct MouthLayers : SyntheticLayers {
  MouthLayers() : SyntheticLayers(300000.0, 4100000.0, 50.0) {}
};

/// The unpaved gaps at the lane joins of `layers` converted with the default options (no lane
/// left out); the conversion must warn of nothing.
inline corsa::test::MouthGapFigures mouth_gaps_of(const Layers& layers) {
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(layers, {}, diagnostics);
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  return corsa::test::mouth_gaps(map, [](const corsa::xodr::LaneRef&, bool) { return false; });
}

}  // namespace corsa::ngii::testing
