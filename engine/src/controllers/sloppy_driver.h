#pragma once

// esmini's sloppyDriver (esminiController SloppyDriverController, its ControllerSloppyDriver),
// emulated: a driver that perturbs the speed and the lateral offset its entity would otherwise
// have, with random targets drawn from esmini's run generator.
//
//   - Longitudinal: every 3 s x U(0.5, 1.5) (a timer on the controller's own clock) it picks a
//     new target factor 1 + sloppiness x U(-0.35, 0.35) of the reference speed (the speed the
//     actions last gave) and blends linearly from the previous target to it over the period.
//   - Lateral: every 1.5 s x U(0.5, 1.5) it picks a new target offset 5 x sloppiness x
//     min(sloppiness, 1) x U(0.5, 1.5) and steers toward it (heading change per step:
//     (-0.02 x (offset + blended target) - 0.05 x heading error) x dt x speed), so the entity
//     drifts to the right of where the actions would have it.
//
// The draws come from one generator for the run, as esmini's: std::mt19937 seeded with the run's
// seed (esmini's `--seed`), each draw libstdc++'s uniform_real_distribution<double> (two 32-bit
// words per draw), reproduced here without the standard library's distributions so that every
// platform draws the same numbers. Entities draw in entity order, the longitudinal pair before the
// lateral pair: the same sequence at any number of threads. Before the first, esmini has drawn
// two numbers per entity of the scenario (EsminiRandom::after_entities).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>

namespace corsa::xosc {
struct ObjectController;
}  // namespace corsa::xosc

namespace corsa::engine::detail {

struct SimState;
struct MotionContext;
struct Entity;

/// esmini's random generator (its SE_Rand): std::mt19937 seeded with the run's seed.
class EsminiRandom {
 public:
  explicit EsminiRandom(uint32_t seed) : engine_(seed) {}

  /// The generator as esmini's is once the scenario's entities are made: esmini draws a random
  /// junction selector angle (uniform in [0, 2 pi)) for every Object it constructs, and
  /// multi_controller's rows fit two such draws for its one entity (docs/openscenario.md,
  /// "esmini's sloppyDriver").
  static EsminiRandom after_entities(uint32_t seed, size_t entities);

  /// A number in [low, high) as libstdc++'s std::uniform_real_distribution<double>{low, high}
  /// draws it from the same engine: generate_canonical from two words, then scaled.
  double real_between(double low, double high);

 private:
  std::mt19937 engine_;
};

/// A timer on the controller's clock (esmini's SE_SimulationTimer): expired once more than its
/// duration less 1e-10 s has passed since its start.
struct SloppyTimer {
  double start = 0.0;     ///< s, controller clock
  double duration = 0.0;  ///< s

  bool expired(double now) const { return now - start > duration - 1e-10; }
  double elapsed(double now) const { return now - start; }
};

/// An entity's sloppy driver: its properties and what it keeps between steps.
struct SloppyDriver {
  double sloppiness = 0.5;    ///< property sloppiness, recommended range [0, 1]
  bool override_mode = true;  ///< property mode: "override" (esmini's default) or "additive"
  double clock = 0.0;         ///< s, advanced by each step the controller takes

  SloppyTimer speed_timer;
  double reference_speed = 0.0;  ///< m/s, the actions' speed
  double initial_speed = 0.0;    ///< m/s, where the current period's blend starts
  double current_speed = 0.0;    ///< m/s, the speed it gave last
  double target_factor = 1.0;    ///< of the reference speed, at the period's end
  double last_command = 0.0;     ///< m/s, the speed command seen last step (an action's change)

  SloppyTimer lateral_timer;
  double offset = 0.0;       ///< m, the lateral displacement it has made (left positive)
  double fuzz_start = 0.0;   ///< m, target offset at the period's start
  double fuzz_target = 0.0;  ///< m, target offset at the period's end
  double heading = 0.0;      ///< rad, its heading relative to the lane
};

/// Whether this ObjectController asks for esmini's sloppyDriver (its `esminiController`
/// property, else the Controller's name).
bool is_sloppy_driver(const xosc::ObjectController& oc);

/// The driver's properties (sloppiness; mode), esmini's defaults for those absent; a
/// sloppiness that is no number warns located at the property.
std::shared_ptr<SloppyDriver> make_sloppy_driver(SimState& state, const xosc::ObjectController& oc);

/// esmini's Activate: timers restarted at clock 0 (so the first period after a later activation
/// ends at once), the speed the entity has as the reference, no offset or target. Its first step
/// is the move of the step whose storyboard activates it (Corsa's storyboard acts before the
/// moves; esmini steps its controllers before its storyboard, so its first step is its next
/// frame's, the same simulated interval).
void activate_sloppy_driver(SloppyDriver& driver, const Entity& entity);

/// Moves every present entity whose sloppy driver is active this step, in entity order (one
/// generator for the run), after the others.
void step_sloppy_drivers(SimState& state, const MotionContext& motion);

}  // namespace corsa::engine::detail
