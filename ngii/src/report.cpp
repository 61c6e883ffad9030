// The corrections report (`corsa convert ngii --report FILE`) and the placements table
// (`--placements FILE`).

#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/ngii/convert.h"

namespace corsa::ngii {
std::string corrections_csv(const std::vector<Correction>& corrections) {
  std::string out = "link_id,field,old_value,new_value,reason,record,kind\n";
  for (const Correction& c : corrections) {
    out += csv_field(c.link_id) + ',' + csv_field(c.field) + ',' + csv_field(c.old_value) + ',' +
           csv_field(c.new_value) + ',' + csv_field(c.reason) + ',' + std::to_string(c.record) +
           ',' + (c.kind == CorrectionKind::kDefect ? "defect" : "relabel") + '\n';
  }
  return out;
}

std::string placements_csv(const std::vector<LinkPlacement>& placements) {
  std::string out = "link_id,road_id,lane_section,lane_id,s_start,s_end\n";
  for (const LinkPlacement& p : placements) {
    out += csv_field(p.link_id) + ',' + csv_field(p.road_id) + ',' + std::to_string(p.section) +
           ',' + std::to_string(p.lane_id) + ',' + format_fixed(p.s_start, 3) + ',' +
           format_fixed(p.s_end, 3) + '\n';
  }
  return out;
}

void write_placements_csv(const std::vector<LinkPlacement>& placements,
                          const std::filesystem::path& path) {
  write_file_atomic(path, placements_csv(placements));
}

void write_corrections_csv(const std::vector<Correction>& corrections,
                           const std::filesystem::path& path) {
  write_file_atomic(path, corrections_csv(corrections));
}

}  // namespace corsa::ngii
