// Suite manifests (schemas/suite.xsd) and suite folders.

#include "corsa/suite/suite.h"

#include <algorithm>
#include <array>
#include <set>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/core/xsd_validator.h"
#include "suite_schema_text.h"

namespace corsa::suite {
namespace {

namespace fs = std::filesystem;

constexpr std::array<std::string_view, 7> kMetricNames = {
    "min_ttc",   "min_distance", "max_deceleration", "max_acceleration",
    "max_speed", "sim_time",     "collisions"};

constexpr const char* kManifestName = "suite.xml";

[[noreturn]] void fail(const std::string& file, const ValidatedElement& e, std::string message) {
  throw InputError(make_error(file, e.line, std::move(message), e.path));
}

// Attribute values have passed the schema, so numbers parse.
double number(const ValidatedElement& e, const std::string& name) {
  return *parse_double(*e.find(name));
}

const std::string* optional(const ValidatedElement& e, const std::string& name) {
  return e.find(name);
}

engine::EndReason end_reason(const std::string& text) {
  if (text == "stopTrigger") return engine::EndReason::kStopTrigger;
  if (text == "duration") return engine::EndReason::kDuration;
  return engine::EndReason::kStoriesComplete;
}

Expectations read_expect(const std::string& file, const ValidatedElement& e) {
  Expectations expect;
  if (const auto* reason = optional(e, "endReason")) expect.end_reason = end_reason(*reason);
  if (const auto* collision = optional(e, "collision")) {
    expect.collision = *collision == "true" || *collision == "1";
  }
  for (const auto& m : e.children) {
    if (m.name == "Monitor") {
      const std::string& value = *m.find("value");
      expect.monitors.emplace_back(*m.find("name"), value == "true" || value == "1");
      continue;
    }
    MetricBound bound;
    bound.metric = *metric_from_string(*m.find("name"));
    if (optional(m, "min")) bound.min = number(m, "min");
    if (optional(m, "max")) bound.max = number(m, "max");
    if (!bound.min && !bound.max) fail(file, m, "<Metric> needs min, max or both");
    if (bound.min && bound.max && *bound.min > *bound.max) {
      fail(file, m, "<Metric> min is above max");
    }
    expect.metrics.push_back(bound);
  }
  return expect;
}

GoldenSpec read_golden(const std::string& file, const fs::path& folder, const std::string& test,
                       const ValidatedElement& e) {
  GoldenSpec golden;
  const std::string* path = optional(e, "file");
  golden.file = (folder / (path ? fs::path(*path) : fs::path("goldens") / (test + ".csv")))
                    .lexically_normal();
  golden.every = static_cast<int64_t>(*parse_int(*e.find("every")));
  golden.line = e.line;
  const double position = number(e, "position");
  const double heading = number(e, "heading");
  for (const char* c : {"x", "y", "z", "s", "t"})
    golden.tolerances.value[*Tolerances::column(c)] = position;
  for (const char* c : {"h", "p", "r"}) golden.tolerances.value[*Tolerances::column(c)] = heading;
  golden.tolerances.value[*Tolerances::column("speed")] = number(e, "speed");
  std::set<std::string> seen;
  for (const auto& t : e.children) {
    const std::string& column = *t.find("column");
    if (!seen.insert(column).second)
      fail(file, t, "tolerance of column '" + column + "' given twice");
    golden.tolerances.value[*Tolerances::column(column)] = number(t, "value");
  }
  return golden;
}

// Run options: the test's attribute, else the suite's (which has schema defaults).
void read_run_options(const ValidatedElement& suite, const ValidatedElement& test, TestCase& out) {
  auto pick = [&](const char* name) {
    const std::string* own = optional(test, name);
    return own ? *own : *suite.find(name);
  };
  out.simulation.dt = *parse_double(pick("dt"));
  out.simulation.duration = *parse_double(pick("duration"));
  out.simulation.seed = static_cast<uint64_t>(*parse_int(pick("seed")));
  out.ego = pick("ego");
}

TestCase read_test(const std::string& file, const fs::path& folder, const ValidatedElement& suite,
                   const ValidatedElement& e) {
  TestCase test;
  test.name = *e.find("name");
  test.line = e.line;
  test.scenario = (folder / *e.find("scenario")).lexically_normal();
  std::error_code error;
  if (!fs::is_regular_file(test.scenario, error)) {
    fail(file, e,
         "scenario '" + *e.find("scenario") + "' of test '" + test.name +
             "' not found (looked for " + test.scenario.string() + ")");
  }
  read_run_options(suite, e, test);
  for (const auto& child : e.children) {
    if (child.name == "Parameter") {
      const std::string& name = *child.find("name");
      for (const auto& [known, value] : test.parameters) {
        if (known == name) fail(file, child, "parameter '" + name + "' is set twice");
      }
      test.parameters.emplace_back(name, *child.find("value"));
    } else if (child.name == "Expect") {
      test.expect = read_expect(file, child);
    } else {
      test.golden = read_golden(file, folder, test.name, child);
    }
  }
  return test;
}

bool is_scenario_text(const std::string& text) {
  // Catalogs and distributions are OpenSCENARIO files too, told apart by the element after
  // FileHeader; the element names are enough here (the full load happens when the test runs).
  return text.find("<Catalog ") == std::string::npos &&
         text.find("<Catalog>") == std::string::npos &&
         text.find("<ParameterValueDistribution") == std::string::npos;
}

Suite folder_suite(const fs::path& folder) {
  Suite suite;
  suite.folder = folder;
  suite.name = fs::absolute(folder).lexically_normal().filename().string();
  if (suite.name.empty())
    suite.name = fs::absolute(folder).lexically_normal().parent_path().filename().string();
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xosc")
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& path : files) {
    if (!is_scenario_text(read_file(path))) continue;
    TestCase test;
    test.name = path.stem().string();
    test.scenario = path.lexically_normal();
    const fs::path golden = folder / "goldens" / (test.name + ".csv");
    std::error_code error;
    if (fs::is_regular_file(golden, error))
      test.golden = GoldenSpec{golden.lexically_normal(), 10, {}, 0};
    suite.tests.push_back(std::move(test));
  }
  if (suite.tests.empty()) {
    throw InputError(make_error(folder.string(), 0,
                                "the suite folder has no suite.xml and no scenario (*.xosc)"));
  }
  return suite;
}

}  // namespace

std::string_view to_string(Metric metric) { return kMetricNames[static_cast<size_t>(metric)]; }

std::optional<Metric> metric_from_string(std::string_view name) {
  for (size_t i = 0; i < kMetricNames.size(); ++i) {
    if (kMetricNames[i] == name) return static_cast<Metric>(i);
  }
  return std::nullopt;
}

std::string_view unit(Metric metric) {
  switch (metric) {
    case Metric::kMinTtc:
    case Metric::kSimTime:
      return "s";
    case Metric::kMinDistance:
      return "m";
    case Metric::kMaxDeceleration:
    case Metric::kMaxAcceleration:
      return "m/s^2";
    case Metric::kMaxSpeed:
      return "m/s";
    case Metric::kCollisions:
      return "";
  }
  return "";
}

Suite parse_suite_manifest(std::string_view xml, const fs::path& file) {
  // The schema is ours: parsing it is checked by the tests, so a failure here is a bug.
  static_assert(kMetricNames.size() == static_cast<size_t>(Metric::kCollisions) + 1);
  const XsdSchema schema(detail::suite_schema_text());
  const std::string name = file.string();
  const ValidatedElement root = schema.validate(xml, name);
  Suite suite;
  suite.name = *root.find("name");
  suite.manifest = file;
  suite.folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  std::set<std::string> names;
  for (const auto& e : root.children) {
    TestCase test = read_test(name, suite.folder, root, e);
    if (!names.insert(test.name).second)
      fail(name, e, "test name '" + test.name + "' is used twice");
    suite.tests.push_back(std::move(test));
  }
  return suite;
}

Suite load_suite(const fs::path& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    const fs::path manifest = path / kManifestName;
    // Whatever is named suite.xml is the manifest (read_file refuses a FIFO or a device).
    if (fs::exists(manifest, error)) return parse_suite_manifest(read_file(manifest), manifest);
    return folder_suite(path);
  }
  if (!fs::exists(path, error)) {
    throw InputError(make_error(path.string(), 0, "no such suite folder or manifest"));
  }
  return parse_suite_manifest(read_file(path), path);
}

}  // namespace corsa::suite
