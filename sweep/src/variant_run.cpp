#include "corsa/sweep/variant_run.h"

#include <chrono>
#include <new>

#include "corsa/core/strings.h"
#include "corsa/engine/outputs.h"
#include "corsa/xosc/scenario.h"

namespace corsa::sweep {
namespace {

// The trajectory rows in memory, with TrajectoryRecorder's rule: every N-th tick, and the last.
class TrajectoryText final : public engine::SimulationObserver {
 public:
  explicit TrajectoryText(int64_t every) : every_(every) { text_ = engine::kTrajectoryHeader; }
  void on_step(const engine::Simulation& simulation) override {
    if (simulation.tick() % every_ == 0) {
      engine::TrajectoryRecorder::append_rows(simulation, text_);
      last_ = simulation.tick();
    }
  }
  std::string finish(const engine::Simulation& simulation) {
    if (last_ != simulation.tick()) {
      engine::TrajectoryRecorder::append_rows(simulation, text_);
    }
    return std::move(text_);
  }

 private:
  int64_t every_;
  int64_t last_ = -1;
  std::string text_;
};

void simulate(SharedInputs& inputs, const VariantSpec& spec, const VariantOutputs& outputs,
              Diagnostics& diagnostics, VariantResult& result,
              std::chrono::steady_clock::time_point start) {
  const xosc::Scenario scenario =
      inputs.load(spec.parameters, diagnostics, spec.simulation.strict,
                  spec.simulation.semantics == engine::Semantics::kEsmini);
  engine::Simulation simulation(scenario, inputs.road_network(scenario), spec.simulation,
                                diagnostics);
  const std::optional<size_t> ego = choose_ego(simulation, spec.ego);
  if (!spec.ego.empty() && !ego) {
    throw InputError(scenario.source.error("the ego entity '" + spec.ego +
                                           "' (--ego) is not an entity of this scenario"));
  }
  MetricsObserver metrics(ego);
  simulation.add_observer(metrics);
  std::optional<engine::TrajectoryRecorder> recorder;
  if (outputs.trajectory) {
    recorder.emplace(*outputs.trajectory, outputs.record_every);
    simulation.add_observer(*recorder);
  }
  std::optional<TrajectoryText> text;
  if (outputs.keep_trajectory_text) {
    text.emplace(outputs.record_every);
    simulation.add_observer(*text);
  }
  simulation.run();
  if (recorder) {
    recorder->finish(simulation);
  }
  if (text) {
    result.trajectory_text = text->finish(simulation);
  }
  result.end_reason = simulation.end_reason();
  result.sim_time = simulation.time();
  result.steps = simulation.steps();
  result.collisions = simulation.collisions().size();
  for (const engine::CollisionRecord& c : simulation.collisions()) {
    result.ego_collisions += ego && (c.first == *ego || c.second == *ego) ? 1 : 0;
    if (result.first_collision.empty()) {
      result.first_collision = simulation.entity(c.first).name + " and " +
                               simulation.entity(c.second).name + " at t=" + format_double(c.time) +
                               " s";
    }
  }
  result.metrics = metrics.metrics();
  result.monitors = simulation.monitors();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (outputs.summary) {
    engine::write_summary(simulation, *outputs.summary, result.wall_seconds);
  }
}

}  // namespace

int exit_status(VariantStatus status) {
  switch (status) {
    case VariantStatus::kOk:
      return 0;
    case VariantStatus::kBadInput:
      return 2;
    case VariantStatus::kInternal:
      return 3;
    case VariantStatus::kSkipped:
      return 0;
  }
  return 3;
}

std::string_view to_string(VariantStatus status) {
  switch (status) {
    case VariantStatus::kOk:
      return "ok";
    case VariantStatus::kBadInput:
      return "error";
    case VariantStatus::kInternal:
      return "internal error";
    case VariantStatus::kSkipped:
      return "skipped";
  }
  return "internal error";
}

VariantResult run_variant(SharedInputs& inputs, const VariantSpec& spec,
                          const VariantOutputs& outputs, Diagnostics& diagnostics) {
  const auto start = std::chrono::steady_clock::now();
  VariantResult result;
  try {
    simulate(inputs, spec, outputs, diagnostics, result, start);
    return result;
  } catch (const xosc::ConstraintViolation& violation) {
    result = VariantResult{};
    result.status = VariantStatus::kSkipped;
    result.error = violation.brief();
  } catch (const InputError& error) {
    result = VariantResult{};  // nothing of a failed run is reported but the failure
    result.status = VariantStatus::kBadInput;
    result.error = error.brief();
  } catch (const std::bad_alloc&) {
    result = VariantResult{};
    result.status = VariantStatus::kInternal;
    result.error = "out of memory";
  } catch (const std::exception& error) {
    result = VariantResult{};
    result.status = VariantStatus::kInternal;
    result.error = std::string("internal error: ") + error.what();
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace corsa::sweep
