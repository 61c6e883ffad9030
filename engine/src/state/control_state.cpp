#include "state/control_state.h"

namespace corsa::engine::detail {

bool parse_controller_kind(const std::string& name, ControllerKind& out) {
  if (name == "default") {
    out = ControllerKind::kDefault;
  } else if (name == "acc") {
    out = ControllerKind::kAcc;
  } else if (name == "dynamics") {
    out = ControllerKind::kDynamics;
  } else if (name == "external") {
    out = ControllerKind::kExternal;
  } else {
    return false;
  }
  return true;
}

}  // namespace corsa::engine::detail
