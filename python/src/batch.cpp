// The work of corsa.sweep and corsa.test (python/corsa/_batch.py turns it into tables): the
// calls `corsa sweep` and `corsa test` make, with the GIL released while the variants run.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <optional>
#include <string>

#include "bindings.h"
#include "corsa/core/atomic_file.h"
#include "corsa/geo/crs_transform.h"
#include "corsa/suite/junit.h"
#include "corsa/suite/suite.h"
#include "corsa/suite/suite_run.h"
#include "corsa/sweep/shard.h"
#include "corsa/sweep/sweep.h"
#include "errors.h"

namespace corsa::python {
namespace py = pybind11;
namespace {

py::object optional_number(const std::optional<double>& value) {
  return value ? py::object(py::float_(*value)) : py::object(py::none());
}

py::dict outcome_dict(const suite::TestOutcome& outcome) {
  py::dict d;
  d["name"] = outcome.name;
  d["verdict"] = std::string(suite::to_string(outcome.verdict));
  d["passed"] = outcome.verdict == suite::Verdict::kPassed;
  d["failures"] = outcome.failures;
  d["error"] = outcome.error;
  d["golden_written"] = outcome.golden_written;
  const sweep::VariantResult& run = outcome.run;
  d["status"] = std::string(sweep::to_string(run.status));
  const bool ran = run.ok();
  d["end_reason"] = ran ? py::object(py::str(std::string(engine::to_string(run.end_reason))))
                        : py::object(py::none());
  d["sim_time"] = ran ? py::object(py::float_(run.sim_time)) : py::object(py::none());
  d["steps"] = ran ? py::object(py::int_(run.steps)) : py::object(py::none());
  d["collisions"] = ran ? py::object(py::int_(run.collisions)) : py::object(py::none());
  d["min_ttc"] = optional_number(run.metrics.min_ttc.value);
  d["min_distance"] = optional_number(run.metrics.min_distance.value);
  d["max_deceleration"] = optional_number(run.metrics.max_deceleration.value);
  d["max_acceleration"] = optional_number(run.metrics.max_acceleration.value);
  d["max_speed"] = optional_number(run.metrics.max_speed.value);
  d["wall_time"] = run.wall_seconds;
  return d;
}

sweep::Shard shard_of(const py::object& shard) {
  if (shard.is_none()) {
    return {};
  }
  const std::string text = py::str(shard);
  if (text == "auto") {
    return sweep::shard_from_environment(
        [](const std::string& name) -> std::optional<std::string> {
          const py::object value = py::module_::import("os").attr("environ").attr("get")(name);
          return value.is_none() ? std::nullopt
                                 : std::optional<std::string>(value.cast<std::string>());
        },
        std::nullopt);
  }
  return sweep::parse_shard(text);
}

py::dict run_sweep(const std::filesystem::path& file, const std::vector<std::string>& grid_specs,
                   const std::filesystem::path& output, size_t jobs, const py::object& shard,
                   bool resume, bool force, uint64_t seed, double dt, double duration,
                   int64_t record_every, bool trajectories, const std::string& ego, bool strict) {
  check_step(dt, duration);
  if (resume && force) {
    throw py::value_error("resume and force exclude each other");
  }
  if (record_every < 1) {
    throw py::value_error("record_every expects a positive integer");
  }
  sweep::SweepOptions options;
  options.shard = shard_of(shard);
  options.output = output;
  options.jobs = jobs;
  options.resume = resume;
  options.force = force;
  options.simulation.seed = seed;
  options.simulation.dt = dt;
  options.simulation.duration = duration;
  options.simulation.geo_projection = geo::geographic_to_projected;  // GeoPositions (PROJ)
  options.record_every = record_every;
  options.trajectories = trajectories;
  options.ego = ego;
  options.simulation.strict = strict;
  Diagnostics diagnostics;
  sweep::SweepReport report;
  {
    py::gil_scoped_release nogil;
    check_output_folder(output);
    std::vector<sweep::GridAxis> grid;
    size_t room = 10'000'000;  // as `corsa sweep --param`: every axis together
    for (const std::string& spec : grid_specs) {
      grid.push_back(sweep::parse_grid_axis(spec, room));
      room -= grid.back().values.size();
    }
    const sweep::VariantPlan plan =
        sweep::VariantPlan::from_file(file, std::move(grid), seed, diagnostics, strict);
    report = sweep::run_sweep(plan, options, diagnostics);
  }
  warn_new(diagnostics, 0);
  py::dict d;
  d["variants"] = report.variants;
  d["ran"] = report.ran;
  d["resumed"] = report.resumed;
  d["failed"] = report.failed;
  d["wall_time"] = report.wall_seconds;
  return d;
}

py::list run_test(const std::filesystem::path& path,
                  const std::optional<std::filesystem::path>& junit, bool update_goldens,
                  size_t jobs, const std::optional<std::filesystem::path>& output) {
  suite::SuiteOptions options;
  options.jobs = jobs;
  options.update_goldens = update_goldens;
  options.geo_projection = geo::geographic_to_projected;  // GeoPositions (PROJ)
  options.output = output;
  Diagnostics diagnostics;
  suite::SuiteReport report;
  {
    py::gil_scoped_release nogil;
    if (output) check_output_folder(*output);
    if (junit) check_output_file(*junit);
    const suite::Suite suite = suite::load_suite(path);
    report = suite::run_suite(suite, options, diagnostics);
    if (junit) write_file_atomic(*junit, suite::junit_xml(suite, report));
  }
  warn_new(diagnostics, 0);
  py::list out;
  for (const suite::TestOutcome& outcome : report.outcomes) out.append(outcome_dict(outcome));
  return out;
}

}  // namespace

void bind_batch(py::module_& m) {
  m.def("_sweep", &run_sweep, py::arg("file"), py::arg("grid"), py::arg("output"), py::arg("jobs"),
        py::arg("shard"), py::arg("resume"), py::arg("force"), py::arg("seed"), py::arg("dt"),
        py::arg("duration"), py::arg("record_every"), py::arg("trajectories"), py::arg("ego"),
        py::arg("strict"));
  m.def("_test", &run_test, py::arg("suite"), py::arg("junit"), py::arg("update_goldens"),
        py::arg("jobs"), py::arg("output"));
}

}  // namespace corsa::python
