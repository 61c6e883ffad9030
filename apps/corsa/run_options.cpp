// Options of `corsa run` shared with the plugin's `run --rig` (run_options.h).

#include "run_options.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "corsa/core/strings.h"
#include "corsa/engine/trajectory_file.h"
#include "corsa/xosc/scenario.h"
#include "output_paths.h"

namespace corsa::cli {
namespace {

void read_npc(const std::string& text, engine::SimulationOptions& options) {
  for (const std::string_view raw : split(text, ',')) {
    const std::string_view item = trim(raw);
    const size_t eq = item.find('=');
    const std::string key(trim(item.substr(0, eq)));
    const auto count = eq == std::string_view::npos ? std::nullopt : parse_int(item.substr(eq + 1));
    if (!count || *count < 0 || *count > 10000) {
      throw UsageError("--npc expects vehicles=N,pedestrians=M (0..10000), got '" +
                       std::string(item) + "'");
    }
    if (key == "vehicles") {
      options.npc.vehicles = static_cast<uint32_t>(*count);
    } else if (key == "pedestrians") {
      options.npc.pedestrians = static_cast<uint32_t>(*count);
    } else {
      const std::vector<std::string> keys{"vehicles", "pedestrians"};
      throw UsageError("--npc: unknown key '" + key + "'" + did_you_mean(key, keys) +
                       " (keys: vehicles, pedestrians)");
    }
  }
}

}  // namespace

engine::Semantics read_semantics(const ParsedArgs& parsed) {
  return parsed.choice("--semantics", {"standard", "esmini"}) == "esmini"
             ? engine::Semantics::kEsmini
             : engine::Semantics::kStandard;
}

namespace {

engine::RecordingThread read_record_thread(const ParsedArgs& parsed) {
  const auto thread = parsed.choice("--record-thread", {"auto", "caller", "writer"});
  return thread == "caller"   ? engine::RecordingThread::kCaller
         : thread == "writer" ? engine::RecordingThread::kWriter
                              : engine::RecordingThread::kAuto;
}

}  // namespace

void declare_run_options(ArgParser& parser) {
  parser.positional("SCENARIO.xosc", "the scenario to run");
  parser.repeated("--param", "NAME=VALUE", "override a global scenario parameter");
  parser.repeated("--value", "NAME=VALUE",
                  "a value UserDefinedValueConditions named NAME compare with");
  parser.option("--dt", "SECONDS", "fixed step (default 0.01)");
  parser.option("--duration", "SECONDS",
                "stop at this simulated time at the latest (default 3600)");
  parser.option("--seed", "N", "run seed for random draws (default 0)");
  parser.option("--controller", "NAME",
                "controller of every vehicle the scenario gives none: default, acc, dynamics");
  parser.option("--record", "FILE.csv|FILE.corsatraj",
                "write the trajectories: CSV (time,entity,x,y,z,h,p,r,...), or binary for "
                ".corsatraj (corsa record export turns it into the same CSV)");
  parser.option("--record-every", "N", "record every N-th step (default 1)");
  parser.option("--record-thread", "auto|caller|writer",
                "where a binary trajectory (FILE.corsatraj only) is encoded: on the run's thread, "
                "on a writer thread of "
                "its own (less wall time when a core is free, more CPU time), or auto (default: "
                "the run's thread, a writer from --threads 2 once the ticks code many rows)");
  parser.option("--summary", "FILE.json", "write the run summary");
  parser.option("--log", "FILE.csv", "write every storyboard transition with its time");
  parser.option("--npc", "vehicles=N,pedestrians=M",
                "add seeded random NPCs: vehicles on driving lanes (car following), pedestrians "
                "walking on sidewalks");
  parser.option(
      "--threads", "N",
      "threads the entities of a step may be moved on (default: every core; a run times "
      "its steps on all of them and on one, now and then, and keeps the faster); from 2, a "
      "binary trajectory may also be encoded on a thread of its own (--record-thread); "
      "results are the same for any number");
  parser.option("--semantics", "standard|esmini",
                "where the standard's text and esmini differ, read as the standard (default) or "
                "as esmini; what the standard leaves open is read as esmini either way "
                "(docs/openscenario.md, differences from esmini)");
  parser.flag("--disable-controllers",
              "ignore the scenario's controllers: every entity moves under the default "
              "controller (or --controller's), as esmini's --disable_controllers");
  parser.flag("--quiet", "no progress bar and no summary line");
  parser.flag("--strict",
              "refuse what would run with a '(read as ...)' warning: rules of the standard the "
              "scenario breaks in a way whose meaning is clear");
}

engine::RunOptions read_run_options(const ParsedArgs& parsed) {
  engine::RunOptions options;
  options.scenario = parsed.positionals().front();
  options.parameters = parsed.assignments("--param");
  options.simulation.values = parsed.assignments("--value");
  if (const auto dt = parsed.number("--dt")) {
    // At least 0.1 ms: a step of 1e-300 s is endless steps, a hang rather than a run.
    if (!(*dt >= 1e-4) || *dt > 10.0) {
      throw UsageError("--dt expects a step in seconds, 0.0001 <= dt <= 10");
    }
    options.simulation.dt = *dt;
  }
  if (const auto duration = parsed.number("--duration")) {
    if (!(*duration >= 0.0) || !std::isfinite(*duration)) {
      throw UsageError("--duration expects a number of seconds >= 0");
    }
    options.simulation.duration = *duration;
  }
  if (const auto seed = parsed.integer("--seed")) {
    if (*seed < 0) {
      throw UsageError("--seed expects a non-negative integer");
    }
    options.simulation.seed = static_cast<uint64_t>(*seed);
  }
  if (auto controller = parsed.choice("--controller", {"default", "acc", "dynamics"})) {
    options.simulation.controller = *controller;
  }
  if (const auto threads = parsed.integer("--threads")) {
    if (*threads < 1 || *threads > 1024) {
      throw UsageError("--threads expects a number of threads, 1 to 1024");
    }
    options.simulation.threads = static_cast<unsigned>(*threads);
  } else {
    options.simulation.threads = std::max(1u, std::thread::hardware_concurrency());
  }
  if (const auto npc = parsed.value("--npc")) {
    read_npc(*npc, options.simulation);
  }
  options.simulation.strict = parsed.flag("--strict");
  options.simulation.semantics = read_semantics(parsed);
  options.simulation.disable_controllers = parsed.flag("--disable-controllers");
  if (const auto every = parsed.integer("--record-every")) {
    if (*every < 1) {
      throw UsageError("--record-every expects a positive integer");
    }
    options.record_every = *every;
  }
  options.record_thread = read_record_thread(parsed);
  options.record = output_file(parsed, "--record");
  // Only a binary trajectory is encoded on a thread of its choosing: refused rather than ignored.
  if (parsed.value("--record-thread") &&
      (!options.record || !engine::is_binary_trajectory(*options.record))) {
    throw UsageError(
        "--record-thread applies to binary trajectories only (--record FILE.corsatraj), got " +
        (options.record ? "--record '" + options.record->generic_string() + "'"
                        : std::string("no --record")));
  }
  options.summary = output_file(parsed, "--summary");
  options.log = output_file(parsed, "--log");
  return options;
}

namespace {

constexpr const char* kDatasetOptions[] = {
    "--rig",         "-o",      "--format",  "--kitti-min-height", "--kitti-max-distance",
    "--force",       "--model", "--preview", "--time-of-day",      "--weather",
    "--entity-model"};

}  // namespace

void declare_dataset_options(ArgParser& parser) {
  parser.section("dataset options (with --rig; docs/datasets.md)");
  parser.option("--rig", "RIG.xml", "sensor rig (schemas/sensor-rig.xsd): capture a dataset");
  parser.option("-o", "DIR", "dataset folder (required with --rig; absent or empty)");
  parser.option("--format", "corsa|kitti",
                "dataset layout: corsa (default) or kitti (adds kitti/training/ image_2, "
                "velodyne, label_2, calib and kitti/ImageSets/)");
  parser.option("--kitti-min-height", "PX",
                "KITTI labels: objects whose visible box is lower become DontCare (default 25)");
  parser.option("--kitti-max-distance", "M",
                "KITTI labels: objects farther away become DontCare (default: the LiDAR's range)");
  parser.flag("--force", "replace a previous dataset in DIR");
  parser.option("--time-of-day", "HH:MM[:SS][ZONE]",
                "override the scenario's time of day: local solar time at the map's place, or "
                "with a zone (Z, +09:00) clock time");
  parser.option("--weather", "KEY=VALUE,...",
                "override the weather: fog=M, rain=MM_PER_H, snow=MM_PER_H, clouds=0..1, "
                "wind=M_PER_S, wind_dir=DEG, wet=0|1, friction=SCALE");
  parser.repeated("--model", "FILE[@X,Y[,HEADING_DEG]]",
                  "add a building model (map metres, z up) at an offset; the scenario's "
                  "SceneGraphFile is loaded too");
  parser.repeated("--entity-model", "WHO=FILE",
                  "a model (glTF/GLB, FBX, OBJ, ...) for the entities without a model3d: WHO is "
                  "an entity's name or a category (car, truck, pedestrian, ...); wins over the "
                  "rig's EntityModel");
  parser.flag("--preview", "also write DIR/preview/contact_sheet.png and camera_birds_eye.mp4");
  parser.section("");
}

std::optional<std::string> dataset_option_given(const ParsedArgs& parsed) {
  for (const char* name : kDatasetOptions) {
    if (parsed.flag(name)) {
      return std::string(name);
    }
  }
  return std::nullopt;
}

}  // namespace corsa::cli
