// `corsa run SCENARIO --rig RIG -o DIR` (plugin side; see run_rig.h and docs/datasets.md).
//
// The run is engine::run_scenario with a `prepare` hook that builds the scene, the sensor system,
// the dataset writer and the capture timeline once the simulation exists. SIGINT and SIGTERM only
// set a flag (nothing else is safe in a handler); the step callback checks it between steps and
// ends the run by throwing, so the capture in progress always completes and the dataset says
// where it stopped.

#include "run_rig.h"

#include <csignal>
#include <iostream>
#include <optional>

#include "commands.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/engine/capture_timeline.h"
#include "corsa/sensors/preview.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/sensor_system.h"
#include "corsa/xosc/scenario.h"
#include "plugin_commands.h"

namespace corsa::cli {
namespace {

// The one piece of process-wide state: a signal can only reach the run through a flag.
volatile std::sig_atomic_t& stop_signal() {
  static volatile std::sig_atomic_t signal_number = 0;
  return signal_number;
}

extern "C" void on_stop_signal(int number) { stop_signal() = number; }

// Installs the handlers for the run and restores the previous ones afterwards.
class SignalScope {
 public:
  SignalScope() {
    stop_signal() = 0;
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &previous_int_);
    sigaction(SIGTERM, &action, &previous_term_);
  }
  ~SignalScope() {
    sigaction(SIGINT, &previous_int_, nullptr);
    sigaction(SIGTERM, &previous_term_, nullptr);
  }
  SignalScope(const SignalScope&) = delete;
  SignalScope& operator=(const SignalScope&) = delete;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

struct Interrupted {
  int signal_number = 0;
};

// Everything that lives for one run, created by the engine's prepare hook.
struct RigSession {
  RigSession(const RigRunOptions& run_options, Diagnostics& run_diagnostics,
             sensors::SensorRig sensor_rig)
      : options(run_options), diagnostics(run_diagnostics), rig(std::move(sensor_rig)) {}

  const RigRunOptions& options;
  Diagnostics& diagnostics;
  sensors::SensorRig rig;
  std::unique_ptr<sensors::Scene> scene;
  std::unique_ptr<sensors::SensorSystem> system;
  std::unique_ptr<sensors::DatasetWriter> writer;
  std::unique_ptr<engine::CaptureTimeline> timeline;
  double start_time_of_day = 0.0;  ///< the scenario's clock at tick 0, s
  int64_t last_tick = 0;
  double last_time = 0.0;

  void prepare(engine::Simulation& simulation);
  void adjust(engine::WorldSnapshot& world);
  void finish(const std::string& status, const std::string& reason) const;
};

void RigSession::prepare(engine::Simulation& simulation) {
  std::vector<std::string> names;
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    names.push_back(simulation.entity(i).name);
  }
  sensors::bind_rig(rig, names);
  std::vector<engine::CaptureSensor> capture_sensors;
  for (const sensors::SensorSpec& s : rig.sensors) {
    capture_sensors.push_back({s.name, s.rate_hz});
  }
  timeline = std::make_unique<engine::CaptureTimeline>(capture_sensors, simulation.scenario(),
                                                       simulation.dt(), diagnostics);
  scene = build_run_scene(simulation, options.models, diagnostics);
  sensors::SensorSystemOptions system_options;
  system_options.seed = simulation.options().seed;
  system_options.location = run_location(simulation, diagnostics);
  system = std::make_unique<sensors::SensorSystem>(rig, *scene, system_options);
  sensors::DatasetRunInfo info;
  info.scenario = options.run.scenario.generic_string();
  for (const auto& p : simulation.scenario().parameters) {
    if (const auto value = simulation.parameter(p.name)) {
      info.parameters.emplace_back(p.name, value->text());
    }
  }
  info.seed = simulation.options().seed;
  info.dt = simulation.dt();
  info.duration = simulation.options().duration;
  info.rig = options.rig.generic_string();
  info.time_of_day = options.time_of_day_text;
  info.weather = options.weather_text;
  info.npc = options.npc_text;
  engine::WorldSnapshot initial;
  simulation.fill_snapshot(initial);
  start_time_of_day = initial.environment.time_of_day;
  // Last, once nothing else can fail: the dataset folder appears only for a run that starts.
  writer = std::make_unique<sensors::DatasetWriter>(*system, options.output, std::move(info),
                                                    options.format, options.force);
  timeline->attach(simulation, *writer, [this](engine::WorldSnapshot& world) { adjust(world); });
}

void RigSession::adjust(engine::WorldSnapshot& world) {
  if (!options.environment.empty()) {
    engine::apply_override(options.environment, start_time_of_day, world.environment);
  }
}

void RigSession::finish(const std::string& status, const std::string& reason) const {
  if (!writer) {
    return;
  }
  sensors::DatasetEnd end;
  end.status = status;
  end.end_reason = reason;
  end.tick = last_tick;
  end.time = last_time;
  for (const engine::CaptureWindow& w : timeline->windows()) {
    end.windows_json.push_back(
        "{\"sensor\": " + json_quote(w.sensor) + ", \"open_tick\": " + std::to_string(w.open_tick) +
        ", \"close_tick\": " +
        (w.close_tick < 0 ? std::string("null") : std::to_string(w.close_tick)) +
        ", \"rate\": " + format_double(w.rate_hz) + "}");
  }
  writer->finish(end);
}

int run_rig_body(std::span<const std::string> args) {
  ArgParser parser("run SCENARIO.xosc --rig RIG.xml -o DIR [options]",
                   "Runs one OpenSCENARIO scenario with a sensor rig and writes a dataset: "
                   "frames.csv, one folder per sensor, calibration, poses, labels, run.json.");
  declare_rig_run_options(parser);
  parser.epilog(
      "Capture windows come from CustomCommandAction type=\"corsa:capture\" (docs/datasets.md);\n"
      "without one the whole run is captured. Ctrl-C stops after the current capture and leaves\n"
      "a consistent dataset (run.json status \"interrupted\"); exit 130 then.\n"
      "example: corsa run scenarios/demo/cut_in_city.xosc --rig scenarios/demo/rig.xml -o out");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  RigRunOptions options = read_rig_run_options(parsed);
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  RigSession session(options, diagnostics, sensors::load_rig(options.rig));
  options.run.prepare = [&session](engine::Simulation& simulation) { session.prepare(simulation); };
  ProgressBar progress("run", options.run.simulation.duration, !options.quiet);
  const SignalScope signals;
  engine::RunReport report;
  try {
    report = engine::run_scenario(options.run, diagnostics, [&](const engine::Simulation& sim) {
      session.last_tick = sim.tick();  // where the run is, for run.json
      session.last_time = sim.time();
      if (stop_signal() != 0) {
        throw Interrupted{static_cast<int>(stop_signal())};
      }
      if (progress.visible() && sim.tick() % 16 == 0) {
        progress.update(sim.time());
      }
    });
  } catch (const Interrupted& interrupted) {
    progress.finish();
    const std::string name = interrupted.signal_number == SIGTERM ? "SIGTERM" : "SIGINT";
    session.finish("interrupted", "interrupted by " + name);
    if (session.writer) {
      std::cerr << "corsa run: interrupted by " << name << "; " << options.output.string()
                << " holds " << session.writer->captures()
                << " complete captures (run.json status \"interrupted\")\n";
    } else {
      std::cerr << "corsa run: interrupted by " << name << " before the first capture\n";
    }
    return 128 + interrupted.signal_number;
  }
  progress.finish();
  session.finish("complete", std::string(engine::to_string(report.end_reason)));
  if (options.preview) {
    const sensors::PreviewReport preview =
        sensors::write_preview(options.output, session.system->rig(), diagnostics);
    if (!options.quiet) {
      std::cout << preview.summary << '\n';
    }
  }
  if (!options.quiet) {
    std::cout << options.run.scenario.string() << ": ended by "
              << engine::to_string(report.end_reason) << " at " << format_fixed(report.sim_time, 2)
              << " s simulated, " << session.writer->captures() << " captures, "
              << session.writer->files() << " files in " << options.output.string() << ", "
              << format_fixed(report.wall_seconds, 1) << " s wall\n";
  }
  return kExitOk;
}

}  // namespace

int plugin_run(std::span<const std::string> args) { return guarded("run", run_rig_body, args); }

}  // namespace corsa::cli
