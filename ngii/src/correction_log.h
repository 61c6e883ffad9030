#pragma once

// Collects the changes made to the source data: each becomes a Correction row (for --report);
// each repair of a source defect also becomes a located note naming the A2_LINK record it
// touched (a repair whose meaning is clear, made on every NGII delivery: the command line prints
// one line counting them, each with --verbose, and refuses them with --strict; docs/ngii.md).
// Relabelling that only follows from the converter's own grouping is listed, with no note.

#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"

namespace corsa::ngii::detail {

class CorrectionLog {
 public:
  CorrectionLog(const Layers& layers, Diagnostics& diagnostics)
      : layers_(layers), diagnostics_(diagnostics) {}

  /// Records that `field` of link `link` (index into layers.links) changed from `old_value` to
  /// `new_value` because of `reason`. Source defects add a located note; relabelling does not.
  void add(int link, std::string field, std::string old_value, std::string new_value,
           std::string reason, CorrectionKind kind = CorrectionKind::kDefect);

  const std::vector<Correction>& corrections() const { return corrections_; }
  std::vector<Correction> take() { return std::move(corrections_); }

 private:
  const Layers& layers_;
  Diagnostics& diagnostics_;
  std::vector<Correction> corrections_;
};

}  // namespace corsa::ngii::detail
