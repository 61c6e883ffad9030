#include "correction_log.h"

namespace corsa::ngii::detail {

void CorrectionLog::add(int link, std::string field, std::string old_value, std::string new_value,
                        std::string reason, CorrectionKind kind) {
  const Link& source = layers_.links[static_cast<size_t>(link)];
  Correction correction{source.id,
                        std::move(field),
                        std::move(old_value),
                        std::move(new_value),
                        std::move(reason),
                        source.record,
                        kind};
  if (kind == CorrectionKind::kRelabel) {
    corrections_.push_back(std::move(correction));
    return;
  }
  Diagnostic note = make_warning(layers_.link_file, 0,
                                 "link " + correction.link_id + ": " + correction.field + " '" +
                                     correction.old_value + "' -> '" + correction.new_value +
                                     "': " + correction.reason);
  note.severity = Severity::kNote;
  note.record = source.record;
  diagnostics_.add(std::move(note));
  corrections_.push_back(std::move(correction));
}

}  // namespace corsa::ngii::detail
