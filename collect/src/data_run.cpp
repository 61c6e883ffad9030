// One data-collection run attached to a simulation (data_run.h).

#include "corsa/collect/data_run.h"

#include <algorithm>
#include <utility>
#include <variant>

#include "corsa/core/strings.h"
#include "corsa/engine/simulation.h"
#include "corsa/sensors/dataset_writer.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/sensor_system.h"
#include "corsa/xosc/scenario.h"

namespace corsa::collect {
namespace {

/// The VisibilityActions of the scenario, the Init's and the events'.
std::vector<const xosc::VisibilityAction*> visibility_actions_of(const xosc::Scenario& scenario) {
  std::vector<const xosc::VisibilityAction*> out;
  const auto take = [&out](const xosc::PrivateAction& action) {
    if (const auto* visibility = std::get_if<xosc::VisibilityAction>(&action)) {
      out.push_back(visibility);
    }
  };
  for (const xosc::InitPrivate& init : scenario.storyboard.init.privates) {
    for (const xosc::PrivateAction& action : init.actions) {
      take(action);
    }
  }
  for (const xosc::Action* action : xosc::event_actions(scenario.storyboard)) {
    if (const auto* p = std::get_if<xosc::PrivateAction>(&action->action)) {
      take(*p);
    }
  }
  return out;
}

/// Warns at each SensorReference of a VisibilityAction that names no sensor of the rig (a rig made
/// for another scenario, a misspelt name): the visibility it names holds for no sensor, so the
/// entity may be hidden from every sensor; an error under --strict.
void check_sensor_references(const xosc::Scenario& scenario, const sensors::SensorRig& rig,
                             bool strict, Diagnostics& diagnostics) {
  std::vector<std::string> known;
  for (const sensors::SensorSpec& s : rig.sensors) {
    known.push_back(s.name);
  }
  for (const xosc::VisibilityAction* action : visibility_actions_of(scenario)) {
    for (const xosc::SensorReference& ref : action->sensor_refs) {
      if (std::find(known.begin(), known.end(), ref.name) != known.end()) {
        continue;
      }
      std::string names;
      for (const std::string& k : known) {
        names += (names.empty() ? "" : ", ") + k;
      }
      const std::string message = "SensorReference '" + clip(ref.name) +
                                  "': the rig has no such sensor" + did_you_mean(ref.name, known) +
                                  " (sensors: " + names + ")";
      if (strict) {
        throw InputError(ref.source.error(message + " (an error under --strict)"));
      }
      diagnostics.add_once(
          "sensor-reference:" + ref.source.file_name() + ":" + std::to_string(ref.source.line) +
              ":" + ref.name,
          ref.source.warning(message + "; the visibility set for it holds for no sensor"));
    }
  }
}

}  // namespace

DataRun::DataRun(const DatasetRunOptions& options, Diagnostics& diagnostics, sensors::SensorRig rig)
    : options_(options), diagnostics_(diagnostics), rig_(std::move(rig)) {}

DataRun::~DataRun() = default;

void DataRun::prepare(engine::Simulation& simulation) {
  std::vector<std::string> names;
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    names.push_back(simulation.entity(i).name);
  }
  sensors::bind_rig(rig_, names);
  check_sensor_references(simulation.scenario(), rig_, simulation.options().strict, diagnostics_);
  // The command line's models first, so that they win over the rig's for the same entity or
  // category.
  std::vector<sensors::EntityModel> models;
  for (const EntityModelSpec& spec : options_.entity_models) {
    models.push_back(resolve_entity_model(spec, names));
  }
  models.insert(models.end(), rig_.entity_models.begin(), rig_.entity_models.end());
  rig_.entity_models = std::move(models);
  std::vector<engine::CaptureSensor> capture_sensors;
  for (const sensors::SensorSpec& s : rig_.sensors) {
    capture_sensors.push_back({s.name, s.rate_hz});
  }
  timeline_ = std::make_unique<engine::CaptureTimeline>(capture_sensors, simulation.scenario(),
                                                        simulation.dt(), diagnostics_);
  scene_ = build_run_scene(simulation, options_.models, rig_, diagnostics_);
  sensors::SensorSystemOptions system_options;
  system_options.seed = simulation.options().seed;
  system_options.location = run_location(simulation, scene_->options().origin, diagnostics_);
  system_options.rgb_instances = options_.format == sensors::DatasetFormat::kKitti;
  system_ = std::make_unique<sensors::SensorSystem>(rig_, *scene_, system_options);
  sensors::DatasetRunInfo info;
  info.scenario = options_.run.scenario.generic_string();
  for (const auto& p : simulation.scenario().parameters) {
    if (const auto value = simulation.parameter(p.name)) {
      info.parameters.emplace_back(p.name, value->text());
    }
  }
  info.seed = simulation.options().seed;
  info.dt = simulation.dt();
  info.duration = simulation.options().duration;
  info.rig = options_.rig.generic_string();
  info.time_of_day = options_.time_of_day_text;
  info.weather = options_.weather_text;
  info.npc = options_.npc_text;
  engine::WorldSnapshot initial;
  simulation.fill_snapshot(initial);
  start_time_of_day_ = initial.environment.time_of_day;
  // Last, once nothing else can fail: the dataset folder appears only for a run that starts.
  writer_ =
      std::make_unique<sensors::DatasetWriter>(*system_, options_.output, std::move(info),
                                               options_.format, options_.replace, options_.kitti);
  if (options_.preview) {
    writer_->stream_preview();
  }
  timeline_->attach(simulation, *writer_, [this](engine::WorldSnapshot& world) { adjust(world); });
}

void DataRun::observe(const engine::Simulation& simulation) {
  last_tick_ = simulation.tick();
  last_time_ = simulation.time();
}

void DataRun::adjust(engine::WorldSnapshot& world) const {
  if (!options_.environment.empty()) {
    engine::apply_override(options_.environment, start_time_of_day_, world.environment);
  }
}

void DataRun::finish(const std::string& status, const std::string& reason) const {
  if (!writer_) {
    return;
  }
  sensors::DatasetEnd end;
  end.status = status;
  end.end_reason = reason;
  end.tick = last_tick_;
  end.time = last_time_;
  end.windows = capture_windows_json(timeline_->windows());
  writer_->finish(end);
  if (writer_->kitti_skipped() > 0) {
    diagnostics_.add(make_warning(
        "", 0,
        "--format kitti: " + std::to_string(writer_->kitti_skipped()) +
            " captures of the camera had no LiDAR scan at the same tick and are not KITTI frames "
            "(give the camera and the LiDAR rates that meet)"));
  }
}

std::optional<sensors::StreamedVideo> DataRun::take_preview_video() {
  return writer_ ? writer_->take_preview_video() : std::nullopt;
}

int64_t DataRun::captures() const { return writer_ ? writer_->captures() : 0; }

int64_t DataRun::files() const { return writer_ ? writer_->files() : 0; }

Json capture_windows_json(std::span<const engine::CaptureWindow> windows) {
  Json json = Json::array();
  for (const engine::CaptureWindow& w : windows) {
    json.push_back({{"sensor", w.sensor},
                    {"open_tick", w.open_tick},
                    {"close_tick", w.close_tick < 0 ? Json(nullptr) : Json(w.close_tick)},
                    {"rate", w.rate_hz}});
  }
  return json;
}

}  // namespace corsa::collect
