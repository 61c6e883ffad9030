// Animation states of an entity at a run time, from the last AnimationAction (OpenSCENARIO 1.3
// §7.4.7.2): what the world snapshot shows the sensors.

#include <algorithm>
#include <cmath>

#include "state/entity.h"

namespace corsa::engine::detail {

double animation_state(const Entity::Animation& animation, double now) {
  if (animation.duration <= 0.0) return animation.to;
  double progress = (now - animation.start) / animation.duration;
  progress = animation.loop ? progress - std::floor(progress) : std::clamp(progress, 0.0, 1.0);
  return animation.from + (animation.to - animation.from) * progress;
}

}  // namespace corsa::engine::detail
