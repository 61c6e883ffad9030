// The corrections report (`corsa convert ngii --report FILE`).

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

void write_corrections_csv(const std::vector<Correction>& corrections,
                           const std::filesystem::path& path) {
  write_file_atomic(path, corrections_csv(corrections));
}

}  // namespace corsa::ngii
