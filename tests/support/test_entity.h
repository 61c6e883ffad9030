#pragma once

#include <utility>

#include "corsa/engine/entity_state.h"
#include "state/entity.h"

namespace corsa::test {

/// An engine entity of the box `box` and the kind `kind` (its info is fixed at construction; the
/// rest of its description keeps the defaults).
inline engine::detail::Entity entity_of(const engine::Box& box,
                                        engine::ObjectKind kind = engine::ObjectKind::kVehicle) {
  engine::EntityInfo info;
  info.kind = kind;
  info.box = box;
  return engine::detail::Entity(std::move(info));
}

}  // namespace corsa::test
