#include <sstream>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/engine/outputs.h"

namespace corsa::engine {
std::string event_log_csv(const Simulation& simulation) {
  std::string out = "time,type,element,transition,state\n";
  for (const TransitionRecord& record : simulation.transitions()) {
    out += format_double(record.time);
    out += ',';
    out += to_string(record.type);
    out += ',';
    out += csv_field(record.path);
    out += ',';
    out += to_string(record.transition);
    out += ',';
    out += to_string(record.state);
    out += '\n';
  }
  return out;
}

void write_event_log(const Simulation& simulation, const std::filesystem::path& file) {
  write_file_atomic(file, event_log_csv(simulation));
}

}  // namespace corsa::engine
