// TimeOfDayCondition (OpenSCENARIO 1.3 §8.3.2): the scenario's time of day (EnvironmentAction's
// TimeOfDay, advancing with the run when animated) compared with a dateTime, as instants.

#include "conditions/condition_makers.h"
#include "state/date_time.h"
#include "state/environment_clock.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TimeOfDayCheck final : public ValueCondition {
 public:
  TimeOfDayCheck(xosc::Rule rule, double reference) : rule_(rule), reference_(reference) {}
  bool holds(const SimState& state) override {
    // Compared as a difference: instants are ~1e9 s, where a relative tolerance is seconds.
    return compare(epoch_seconds(current_date_time(state)) - reference_, rule_, 0.0);
  }

 private:
  xosc::Rule rule_;
  double reference_;  ///< s since 1970 UTC
};

}  // namespace

std::unique_ptr<ValueCondition> make_time_of_day(const xosc::TimeOfDayCondition& c,
                                                 const SimState&) {
  const auto when = parse_date_time(c.date_time);
  if (!when) {
    throw InputError(c.source.error("dateTime '" + c.date_time +
                                    "' is not an xsd:dateTime (YYYY-MM-DDThh:mm:ss)"));
  }
  return std::make_unique<TimeOfDayCheck>(c.rule, epoch_seconds(*when));
}

}  // namespace corsa::engine::detail
