// `corsa validate FILE...`: loads each OpenSCENARIO (.xosc: scenario, catalog or parameter
// distribution) or OpenDRIVE (.xodr) file with the real loaders and reports what is wrong as
// `file:line: error: message`, or as JSON for tools. Exit 0 when every file is valid, 2 if not.

#include <iostream>
#include <variant>

#include "args.h"
#include "commands.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/json.h"
#include "corsa/core/strings.h"
#include "corsa/engine/road_network_check.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "corsa/xosc/scenario.h"

namespace corsa::cli {
namespace {

struct FileReport {
  std::string file;
  std::string kind;     // scenario, catalog, distribution, opendrive
  std::string summary;  // one line for humans, when valid
  std::vector<Diagnostic> diagnostics;
  bool valid = false;
};

std::string count(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

void describe(const xosc::Document& document, FileReport& report) {
  if (const auto* scenario = std::get_if<xosc::Scenario>(&document)) {
    report.kind = "scenario";
    report.summary = "OpenSCENARIO " + std::to_string(scenario->header.rev_major) + "." +
                     std::to_string(scenario->header.rev_minor) + " scenario, " +
                     count(scenario->entities.objects.size(), "entity", "entities") + ", " +
                     count(scenario->storyboard.stories.size(), "story", "stories");
    if (!scenario->catalog_files.empty()) {
      report.summary +=
          ", " + count(scenario->catalog_files.size(), "catalog file", "catalog files");
    }
  } else if (const auto* catalog = std::get_if<xosc::Catalog>(&document)) {
    report.kind = "catalog";
    const size_t entries = catalog->vehicles.size() + catalog->controllers.size() +
                           catalog->pedestrians.size() + catalog->misc_objects.size() +
                           catalog->environments.size() + catalog->maneuvers.size() +
                           catalog->trajectories.size() + catalog->routes.size();
    report.summary = "catalog '" + catalog->name + "', " + count(entries, "entry", "entries");
  } else {
    const auto& distribution = std::get<xosc::ParameterValueDistribution>(document);
    report.kind = "distribution";
    report.summary = "parameter distribution over " + distribution.scenario_file.filepath + ", " +
                     count(xosc::variant_count(distribution), "variant", "variants");
  }
}

FileReport check_file(const std::string& file, const xosc::LoadOptions& options) {
  FileReport report;
  report.file = file;
  Diagnostics diagnostics;
  try {
    const std::filesystem::path path(file);
    if (to_lower(path.extension().string()) == ".xodr") {
      report.kind = "opendrive";
      const xodr::Map map = xodr::Map::load(path, diagnostics);
      if (options.strict) xodr::refuse_lenient_readings(map.data());
      report.summary = "OpenDRIVE map";
    } else {
      report.kind = "openscenario";
      // Roads and lanes named by positions are checked against the map too, with the
      // document's other errors: a run would check each only when it placed something there.
      // With it, the lenient readings a run makes as it meets an element are warned about too.
      xosc::LoadOptions with_map = options;
      with_map.road_network_check = std::make_shared<engine::MapReferenceCheck>(options.strict);
      describe(xosc::load_document(path, with_map, diagnostics), report);
    }
    report.valid = true;
  } catch (const InputError& error) {
    report.diagnostics = diagnostics.all();
    report.diagnostics.insert(report.diagnostics.end(), error.diagnostics().begin(),
                              error.diagnostics().end());
    return report;
  }
  report.diagnostics = diagnostics.all();
  return report;
}

void print_json(const std::vector<FileReport>& reports, bool all_valid) {
  Json files = Json::array();
  for (const FileReport& r : reports) {
    Json diagnostics = Json::array();
    for (const Diagnostic& d : r.diagnostics) {
      diagnostics.push_back({{"severity", severity_name(d.severity)},
                             {"file", d.file},
                             {"line", d.line},
                             {"message", d.message},
                             {"path", d.path}});
    }
    files.push_back({{"file", r.file},
                     {"kind", r.kind},
                     {"valid", r.valid},
                     {"diagnostics", std::move(diagnostics)}});
  }
  std::cout << json_compact({{"valid", all_valid}, {"files", std::move(files)}}) << "\n";
}

}  // namespace

int command_validate(std::span<const std::string> args) {
  ArgParser parser("validate FILE... [--json] [--strict] [--param NAME=VALUE]...",
                   "Checks OpenSCENARIO (.xosc) and OpenDRIVE (.xodr) files; prints file:line "
                   "errors.");
  parser.positional("FILE", "files to check (.xosc scenario, catalog or distribution; .xodr)", 1,
                    -1);
  parser.flag("--json", "print one JSON report on stdout instead of messages");
  parser.repeated("--param", "NAME=VALUE", "override a global scenario parameter");
  parser.flag("--strict",
              "report lenient readings ('(read as ...)' warnings: rules of the standard broken "
              "in a way whose meaning is clear) as errors");
  parser.epilog(
      "Exit code 0 when every file is valid, 2 when any is not.\n"
      "example: corsa validate scenarios/cut_in.xosc --param EgoSpeed=30");
  const ParsedArgs parsed = parser.parse(args);
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  xosc::LoadOptions options;
  options.strict = parsed.flag("--strict");
  options.parameters = parsed.assignments("--param");
  std::vector<FileReport> reports;
  bool all_valid = true;
  for (const auto& file : parsed.positionals()) {
    reports.push_back(check_file(file, options));
    all_valid = all_valid && reports.back().valid;
  }
  if (parsed.flag("--json")) {
    print_json(reports, all_valid);
  } else {
    for (const auto& report : reports) {
      for (const auto& diagnostic : report.diagnostics) {
        std::cerr << diagnostic.format() << '\n';
      }
      if (report.valid) {
        std::cout << report.file << ": ok (" << report.summary << ")\n";
      }
    }
  }
  return all_valid ? kExitOk : kExitBadInput;
}

}  // namespace corsa::cli
