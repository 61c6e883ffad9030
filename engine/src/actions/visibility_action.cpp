// VisibilityAction (OpenSCENARIO 1.3 §7.4.5): whether the image generator (graphics), the
// sensors and the other traffic participants see the actor. The sensors flag goes to the world
// snapshot (EntitySnapshot::visible); traffic invisibility hides the actor from car following.
// A SensorReferenceSet names the sensors the flag is for; "for the other not named sensors
// implicitly the opposite applies" (1.3 model text of VisibilityAction.sensorReferenceSet): the
// snapshot's flag is then the opposite one, and the named sensors its exceptions.

#include "actions/action_makers.h"
#include "controllers/controllers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class VisibilityInstance final : public InstantAction {
 public:
  explicit VisibilityInstance(const xosc::VisibilityAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    // A flag the file left out keeps the visibility it had (a lenient reading).
    ControlState& control = control_of(context.state, *context.actor);
    if (action_.sensors) {
      const bool named = !action_.sensor_refs.empty();
      context.entity().write_state().visible = named ? !*action_.sensors : *action_.sensors;
      control.sensor_exceptions.clear();
      for (const xosc::SensorReference& ref : action_.sensor_refs) {
        control.sensor_exceptions.push_back(ref.name);
      }
    }
    if (action_.traffic) control.traffic_visible = *action_.traffic;
    if (action_.graphics) control.graphics_visible = *action_.graphics;
  }

 private:
  const xosc::VisibilityAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_visibility_action(const xosc::VisibilityAction& action) {
  return std::make_unique<VisibilityInstance>(action);
}

}  // namespace corsa::engine::detail
