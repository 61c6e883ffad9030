#include "lane_numbers.h"

#include <string>
#include <vector>

namespace corsa::ngii::detail {
namespace {

std::string sequence_text(const Network& net, const std::vector<int>& links) {
  std::string text;
  for (const int link : links) {
    text += (text.empty() ? "" : " ") + std::to_string(net.source(link).lane_no);
  }
  return text;
}

// The reasons quote the LaneNo values as read (Link::lane_no), not the partly corrected ones.

/// Why the ordinary lanes of a run need renumbering (empty when they read 1..m), and whether
/// that is only a relabelling (the run is a road split off a lateral group whose numbers
/// simply continue across the split).
std::string run_reason(const Network& net, const LateralStructure& lateral, const LaneRun& run,
                       size_t pockets, CorrectionKind& kind) {
  kind = CorrectionKind::kDefect;
  const auto lane_no = [&](size_t k) { return net.source(run.links[k]).lane_no; };
  const std::string seq = "lanes left to right read " + sequence_text(net, run.links);
  bool consecutive = true;
  for (size_t k = pockets; k + 1 < run.links.size(); ++k) {
    consecutive = consecutive && lane_no(k + 1) == lane_no(k) + 1;
  }
  if (pockets == run.links.size()) {
    return {};
  }
  const int first = lane_no(pockets);
  if (consecutive && first == 1) {
    return {};
  }
  if (consecutive && first > 1 && run.position > 0) {
    const auto& group = lateral.groups[static_cast<size_t>(run.group)];
    const int before = group[static_cast<size_t>(run.position) - 1];
    if (net.source(before).lane_no == first - 1) {
      kind = CorrectionKind::kRelabel;
      return seq + ", continuing the numbers of link " + net.source(before).id +
             " beside it, which the conversion puts in another road; that road's lanes start "
             "at 1";
    }
  }
  if (consecutive && first > 1) {
    return seq + "; a road's lanes start at 1 (the innermost lane)";
  }
  return seq + "; lane numbers must be consecutive from 1";
}

}  // namespace

void correct_lane_numbers(Network& network, const LateralStructure& lateral, CorrectionLog& log) {
  for (const LaneRun& run : lateral.runs) {
    size_t pockets = 0;
    while (pockets < run.links.size() &&
           is_pocket_number(network.links[static_cast<size_t>(run.links[pockets])].lane_no)) {
      ++pockets;
    }
    CorrectionKind run_kind = CorrectionKind::kDefect;
    const std::string reason = run_reason(network, lateral, run, pockets, run_kind);
    const std::string seq = sequence_text(network, run.links);
    for (size_t k = 0; k < run.links.size(); ++k) {
      LinkState& state = network.links[static_cast<size_t>(run.links[k])];
      const int expected =
          k < pockets ? 90 + static_cast<int>(pockets - k) : static_cast<int>(k - pockets) + 1;
      if (state.lane_no == expected) {
        continue;
      }
      std::string why;
      CorrectionKind kind = CorrectionKind::kDefect;
      if (state.lane_no == 0) {
        why = "LaneNo missing; numbered by position (" + seq + ")";
      } else if (k < pockets) {
        // The pockets' order is a usage convention (no spec wording was found): relabelled.
        kind = CorrectionKind::kRelabel;
        why =
            "left-turn pockets are numbered outward from 91 (lanes left to right read " + seq + ")";
      } else if (is_pocket_number(state.lane_no)) {
        why =
            "left-turn pocket number inside the road, not on the median side (lanes left to "
            "right read " +
            seq + ")";
      } else {
        why = reason;
        kind = run_kind;
      }
      const int old_value = state.lane_no;
      state.lane_no = expected;
      log.add(run.links[k], "LaneNo", std::to_string(old_value), std::to_string(expected), why,
              kind);
    }
  }
}

}  // namespace corsa::ngii::detail
