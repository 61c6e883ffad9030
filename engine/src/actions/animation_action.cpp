// AnimationAction (OpenSCENARIO 1.3 §7.4.7.2, an AppearanceAction): changes how an entity looks,
// not how it moves. The animation state is kept on the entity (state/entity.h) and reaches the
// sensors through the world snapshot (EntitySnapshot::animations). The action completes after its
// animationDuration; with loop, the animation keeps cycling after the action completed.
// (LightStateAction, the other AppearanceAction, is in light_state_action.cpp.)

#include "actions/action_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

std::string animation_name(const xosc::AnimationType& type) {
  return std::visit(
      [](const auto& a) -> std::string {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, xosc::ComponentAnimation>) {
          if (const auto* component = std::get_if<xosc::VehicleComponentType>(&a.component)) {
            return std::string(xosc::to_string(*component));
          }
          return std::get<std::string>(a.component);
        } else if constexpr (std::is_same_v<T, xosc::PedestrianAnimation>) {
          if (a.motion) return std::string(xosc::to_string(*a.motion));
          return a.user_defined_pedestrian_animation.value_or("pedestrian");
        } else if constexpr (std::is_same_v<T, xosc::AnimationFile>) {
          return a.file.filepath;
        } else {
          return a.type;
        }
      },
      type);
}

// Runs until its duration has passed (0: completes at once).
class TimedAppearance : public ActionInstance {
 public:
  explicit TimedAppearance(double duration) : duration_(duration) {}
  void step(ActionContext& context) override { done_ = context.state.now() - start_ >= duration_; }
  bool finished() const override { return done_; }

 protected:
  void begin(const ActionContext& context) {
    start_ = context.state.now();
    done_ = duration_ <= 0.0;
  }

 private:
  double duration_;
  double start_ = 0.0;
  bool done_ = false;
};

class AnimationInstance final : public TimedAppearance {
 public:
  explicit AnimationInstance(const xosc::AnimationAction& action)
      : TimedAppearance(action.animation_duration.value_or(0.0)), action_(action) {}
  void start(ActionContext& context) override {
    begin(context);
    const double now = context.state.now();
    auto& animations = context.entity().animations;
    const std::string name = animation_name(action_.animation_type);
    const auto previous = animations.find(name);
    Entity::Animation animation;
    animation.from = previous == animations.end() ? 0.0 : animation_state(previous->second, now);
    animation.to = action_.state.value_or(1.0);
    animation.start = now;
    animation.duration = action_.animation_duration.value_or(0.0);
    animation.loop = action_.loop.value_or(false);
    if (animation.loop) animation.from = 0.0;  // a loop runs the whole range each time
    animations[name] = animation;
  }

 private:
  const xosc::AnimationAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_animation_action(const xosc::AnimationAction& action) {
  return std::make_unique<AnimationInstance>(action);
}

}  // namespace corsa::engine::detail
