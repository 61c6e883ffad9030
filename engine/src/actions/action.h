#pragma once

// The small interface every action implements (OpenSCENARIO 1.3 §7 actions, §8.4.1 their
// execution). An Action element of the storyboard runs one ActionInstance per actor (private
// actions) or one instance (global and user-defined actions). New actions are new files
// implementing this interface plus one line in action_factory.cpp.

#include <cstdint>
#include <optional>

#include "state/entity.h"

namespace corsa::engine::detail {

struct SimState;

/// What an action works on: the run state and, for private actions, its actor.
struct ActionContext {
  SimState& state;
  std::optional<uint32_t> actor;
  bool init = false;  ///< part of the Storyboard's Init (before time starts)

  Entity& entity() const;
};

class ActionInstance {
 public:
  virtual ~ActionInstance() = default;

  /// The domains (ActionDomain bits) this action controls on its actor. Starting an action
  /// stops the running one of the same entity and domain (it is overridden, §7.4).
  virtual uint8_t domains() const { return kDomainNone; }
  /// startTransition: instantaneous actions do all their work here.
  virtual void start(ActionContext& context) = 0;
  /// One step of dt: set the actor's commands for the end of the step (before the controllers
  /// move). Called once per step while running.
  virtual void step(ActionContext& context) { (void)context; }
  /// True once the action reached its goal (endTransition).
  virtual bool finished() const = 0;
  /// The actor was put elsewhere (a TeleportAction) while this action holds one of its domains.
  /// An action whose motion is measured from where the actor was recomputes it from where the
  /// actor is now; the others carry on unchanged.
  virtual void actor_placed(ActionContext& context) { (void)context; }

  /// Stopped before it finished (overridden, or its Act/Storyboard was stopped).
  void mark_stopped() { stopped_ = true; }
  bool stopped() const { return stopped_; }
  bool done() const { return stopped_ || finished(); }

 private:
  bool stopped_ = false;
};

/// Stops the running actions that hold any of `domains` (ActionDomain bits) on `entity`, except
/// `keep`, and takes every domain they held from them (they are overridden, §7.4).
void stop_domain_owners(Entity& entity, uint8_t domains, const ActionInstance* keep = nullptr);

/// An action that completes the moment it starts (Parameter/Variable set, Environment, ...).
class InstantAction : public ActionInstance {
 public:
  bool finished() const override { return true; }
};

}  // namespace corsa::engine::detail
