#pragma once

// xosc actions -> run-time instances (one per actor for private actions).

#include <memory>

#include "actions/action.h"
#include "corsa/xosc/storyboard.h"

namespace corsa::engine::detail {

std::unique_ptr<ActionInstance> make_private_action(const xosc::PrivateAction& action);
std::unique_ptr<ActionInstance> make_global_action(const xosc::GlobalAction& action);
std::unique_ptr<ActionInstance> make_user_defined_action(const xosc::UserDefinedAction& action);

/// True for private actions (they run once per actor of their ManeuverGroup).
inline bool is_private(const xosc::Action& action) {
  return std::holds_alternative<xosc::PrivateAction>(action.action);
}

/// One instance of a storyboard Action (for `actor` when it is private).
std::unique_ptr<ActionInstance> make_action(const xosc::Action& action);

}  // namespace corsa::engine::detail
