// Loading OpenSCENARIO documents: the scenario's top level (declarations, catalog locations,
// road network, entities, storyboard), the checks that need the whole document, and the
// dispatch on the document kind.

#include <algorithm>

#include "corsa/core/atomic_file.h"
#include "file_paths.h"
#include "osc09_mapping.h"
#include "parsers.h"
#include "references.h"

namespace corsa::xosc {
namespace {

const Element* checked_root(ParseContext& ctx, const XmlFile& xml) {
  const Element* root = xml.document->RootElement();
  if (std::string_view(root->Name()) != "OpenSCENARIO") {
    ctx.fail(root, "not an OpenSCENARIO document: the root element is <" +
                       std::string(root->Name()) + ">");
  }
  return root;
}

std::filesystem::path resolve_path(const std::filesystem::path& base, const std::string& path) {
  return (base / std::filesystem::path(path)).lexically_normal();
}

CatalogLocations parse_catalog_locations(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "CatalogLocations");
  CatalogLocations locations;
  locations.source = ctx.source(e);
  const std::pair<const char*, std::optional<CatalogDirectory>*> slots[] = {
      {"VehicleCatalog", &locations.vehicle},         {"ControllerCatalog", &locations.controller},
      {"PedestrianCatalog", &locations.pedestrian},   {"MiscObjectCatalog", &locations.misc_object},
      {"EnvironmentCatalog", &locations.environment}, {"ManeuverCatalog", &locations.maneuver},
      {"TrajectoryCatalog", &locations.trajectory},   {"RouteCatalog", &locations.route}};
  for (const auto& [name, slot] : slots) {
    if (const Element* location = kids.opt(name)) {
      Children location_kids(ctx, location, "CatalogLocation");
      // A location needs its Directory (§9.2 CatalogLocations); esmini's examples write an
      // empty <RouteCatalog/> for "no route catalog", which is what leaving it out means.
      if (location->FirstChildElement() == nullptr) {
        ctx.lenient(location, "<" + std::string(name) + "> without a <Directory>",
                    "no " + std::string(name));
        continue;
      }
      const Element* directory = location_kids.one("Directory");
      Children(ctx, directory, "Directory");
      CatalogDirectory value;
      value.path = ctx.req_str(directory, "path");
      value.resolved =
          resolve_named_path(ctx, directory, value.path, PathKind::kDirectory, "catalog directory");
      value.source = ctx.source(directory);
      *slot = std::move(value);
    }
  }
  return locations;
}

TrafficSignalController parse_signal_controller(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TrafficSignalController");
  TrafficSignalController controller;
  controller.name = ctx.req_str(e, "name");
  controller.delay = ctx.opt_double(e, "delay");
  controller.reference = ctx.opt_str(e, "reference");
  for (const Element* p : kids.all("Phase")) {
    Children phase_kids(ctx, p, "Phase");
    Phase phase;
    phase.name = ctx.req_str(p, "name");
    phase.duration = ctx.req_double(p, "duration");
    for (const Element* s : phase_kids.all("TrafficSignalState")) {
      Children(ctx, s, "TrafficSignalState");
      phase.states.push_back(
          {ctx.req_str(s, "trafficSignalId"), ctx.req_str(s, "state"), ctx.source(s)});
    }
    if (const Element* group = phase_kids.opt("TrafficSignalGroupState")) {
      Children(ctx, group, "TrafficSignalGroupState");
      phase.group_state = ctx.req_str(group, "state");
    }
    phase.source = ctx.source(p);
    controller.phases.push_back(std::move(phase));
  }
  controller.source = ctx.source(e);
  return controller;
}

// The map a LogicFile names. CARLA's scenarios name a CARLA town ("Town04"), which CARLA loads
// by name: a path without extension that names no file is read as the same path with ".xodr"
// when that file exists (found as any map file is, from the scenario's folder and above).
std::filesystem::path resolve_map_path(ParseContext& ctx, const Element* logic,
                                       const std::string& filepath) {
  std::filesystem::path path =
      resolve_named_path(ctx, logic, filepath, PathKind::kFile, "map file");
  std::error_code error;
  if (!ctx.options().check_files || filepath.empty() ||
      !std::filesystem::path(filepath).extension().empty() ||
      std::filesystem::is_regular_file(path, error)) {
    return path;
  }
  const std::string named = filepath + ".xodr";
  std::filesystem::path candidate =
      resolve_named_path(ctx, logic, named, PathKind::kFile, "map file");
  if (!std::filesystem::is_regular_file(candidate, error)) return path;
  ctx.lenient(logic,
              "map file '" + clip(filepath) + "' has no extension and names no file (a CARLA " +
                  "town name: CARLA loads its maps by name)",
              "'" + clip(named) + "', " + clip(candidate.string()));
  return candidate;
}

RoadNetwork parse_road_network(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RoadNetwork");
  RoadNetwork network;
  network.source = ctx.source(e);
  if (const Element* logic = kids.opt("LogicFile")) {
    network.logic_file = parse_file(ctx, logic);
    network.logic_file_path = resolve_map_path(ctx, logic, network.logic_file->filepath);
    std::error_code error;
    if (ctx.options().check_files &&
        !std::filesystem::is_regular_file(network.logic_file_path, error)) {
      // Reported, and the rest of the document is still checked.
      const bool relative = std::filesystem::path(network.logic_file->filepath).is_relative();
      ctx.error(logic, "map file '" + clip(network.logic_file->filepath) +
                           "' not found (looked for " + clip(network.logic_file_path.string()) +
                           (relative ? ", and for the same path from the " +
                                           std::to_string(kAncestorLevels) + " folders above"
                                     : std::string()) +
                           ")");
    }
  }
  if (const Element* scene = kids.opt("SceneGraphFile")) {
    network.scene_graph_file = parse_file(ctx, scene);
    network.scene_graph_file_path =
        resolve_path(ctx.file().directory, network.scene_graph_file->filepath);
    std::error_code error;
    if (ctx.options().check_files &&
        !std::filesystem::exists(network.scene_graph_file_path, error)) {
      ctx.warn_once(scene, "scene-graph",
                    "scene graph file '" + network.scene_graph_file->filepath +
                        "' not found (Corsa does not use it)");
    }
  }
  if (const Element* signals = kids.opt("TrafficSignals")) {
    Children signal_kids(ctx, signals, "TrafficSignals");
    for (const Element* controller : signal_kids.all("TrafficSignalController")) {
      ctx.recover([&] {
        network.traffic_signal_controllers.push_back(parse_signal_controller(ctx, controller));
      });
    }
  }
  if (const Element* area = kids.opt("UsedArea")) {
    Children area_kids(ctx, area, "UsedArea");
    for (const Element* position : area_kids.at_least("Position", 2)) {
      network.used_area.push_back(parse_position(ctx, position));
    }
  }
  return network;
}

void parse_variables_and_monitors(ParseContext& ctx, Children& kids, Scenario& scenario) {
  if (const Element* variables = kids.opt("VariableDeclarations")) {
    Children variable_kids(ctx, variables, "VariableDeclarations");
    for (const Element* v : variable_kids.all("VariableDeclaration")) {
      ctx.recover([&] {
        Children(ctx, v, "VariableDeclaration");
        VariableDeclaration variable;
        variable.name = ctx.req_str(v, "name");
        variable.type = ctx.req_enum<ParameterType>(v, "variableType");
        const std::string text = ctx.req_str(v, "value");
        if (!ctx.variables.emplace(variable.name, variable.type).second) {
          ctx.error(v, "variable '" + clip(variable.name) + "' is declared twice");
        }
        const auto value =
            ctx.typed_value(v, variable.type, text, "variable '" + variable.name + "'");
        if (!value) {
          ctx.fail(v, "variable '" + clip(variable.name) + "': '" + clip(text) +
                          "' is not a valid " + std::string(to_string(variable.type)));
        }
        variable.value = *value;
        variable.source = ctx.source(v);
        scenario.variables.push_back(std::move(variable));
      });
    }
  }
  if (const Element* monitors = kids.opt("MonitorDeclarations")) {
    Children monitor_kids(ctx, monitors, "MonitorDeclarations");
    for (const Element* m : monitor_kids.all("MonitorDeclaration")) {
      ctx.recover([&] {
        Children(ctx, m, "MonitorDeclaration");
        MonitorDeclaration monitor{ctx.req_str(m, "name"), ctx.req_bool(m, "value"), ctx.source(m)};
        if (!ctx.monitors.insert(monitor.name).second) {
          ctx.fail(m, "monitor '" + clip(monitor.name) + "' is declared twice");
        }
        scenario.monitors.push_back(std::move(monitor));
      });
    }
  }
}

std::vector<ParameterAssignment> option_overrides(const LoadOptions& options) {
  std::vector<ParameterAssignment> overrides;
  const auto origin = std::make_shared<const std::string>("--param");
  for (const auto& [name, value] : options.parameters) {
    overrides.push_back({name, value, Source{origin, 0}});
  }
  return overrides;
}

// An entity the Init places by no TeleportAction but has follow a trajectory: a run places it
// at the trajectory's start with this warning (engine/src/storyboard/init_actions.cpp), which a
// load for `corsa validate` gives too (ParseContext::run_reading). Entities named through an
// EntitySelection are left to the run.
void warn_trajectory_placements(ParseContext& ctx, const Scenario& scenario) {
  const auto& privates = scenario.storyboard.init.privates;
  const auto teleported = [&](const std::string& entity) {
    return std::any_of(privates.begin(), privates.end(), [&](const InitPrivate& other) {
      return other.entity_ref == entity &&
             std::any_of(other.actions.begin(), other.actions.end(), [](const auto& action) {
               return std::holds_alternative<TeleportAction>(action);
             });
    });
  };
  std::vector<std::string> placed;  // by their first trajectory, which alone is warned about
  for (const InitPrivate& init : privates) {
    if (scenario.entities.find_object(init.entity_ref) == nullptr || teleported(init.entity_ref)) {
      continue;
    }
    for (const PrivateAction& action : init.actions) {
      const auto* follow = std::get_if<FollowTrajectoryAction>(&action);
      if (follow != nullptr &&
          std::find(placed.begin(), placed.end(), init.entity_ref) == placed.end()) {
        placed.push_back(init.entity_ref);
        ctx.run_reading(
            follow->source,
            "entity '" + init.entity_ref + "' has no initial position (no TeleportAction in Init)",
            "the start of the trajectory it follows");
      }
    }
  }
}

Scenario parse_scenario_root(ParseContext& ctx, const Element* root, Children& kids,
                             const std::filesystem::path& path) {
  Scenario scenario;
  scenario.path = path;
  scenario.source = ctx.source(root);
  ctx.recover([&] { scenario.header = parse_file_header(ctx, kids.one("FileHeader")); });
  scenario.parameters = ctx.push_scope(kids.opt("ParameterDeclarations"),
                                       option_overrides(ctx.options()), true, "the scenario");
  ScopeGuard guard(ctx);
  for (const auto& parameter : scenario.parameters) {
    ctx.global_parameters.insert(parameter.name);
  }
  parse_variables_and_monitors(ctx, kids, scenario);
  ctx.recover([&] {
    scenario.catalog_locations = parse_catalog_locations(ctx, kids.one("CatalogLocations"));
  });
  const bool network_read = ctx.recover(
      [&] { scenario.road_network = parse_road_network(ctx, kids.one("RoadNetwork")); });
  for (const auto& controller : scenario.road_network.traffic_signal_controllers) {
    auto& phases = ctx.signal_controllers[controller.name];
    for (const auto& phase : controller.phases) phases.push_back(phase.name);
  }
  CatalogResolver catalogs(scenario.catalog_locations);
  ctx.catalogs = &catalogs;
  ctx.recover([&] { scenario.entities = parse_entities(ctx, kids.one("Entities")); });
  ctx.recover([&] { scenario.storyboard = parse_storyboard(ctx, kids.one("Storyboard")); });
  report_carla_criteria(ctx);
  ctx.catalogs = nullptr;
  scenario.catalog_files = catalogs.files_read();
  check_entity_references(ctx, scenario.entities);
  resolve_storyboard_references(ctx, scenario.storyboard);
  warn_trajectory_placements(ctx, scenario);
  if (const auto& check = ctx.options().road_network_check; check && network_read) {
    std::vector<Diagnostic> errors =
        check->check(scenario.road_network, ctx.road_uses(), ctx.diagnostics());
    if (!errors.empty()) {
      ctx.record(InputError(std::move(errors)));
    }
  }
  return scenario;
}

// The element after FileHeader decides what an OpenSCENARIO document is.
DocumentKind kind_of(const Element* root) {
  if (root->FirstChildElement("Catalog") != nullptr) return DocumentKind::kCatalog;
  if (root->FirstChildElement("ParameterValueDistribution") != nullptr) {
    return DocumentKind::kDistribution;
  }
  return DocumentKind::kScenario;
}

Catalog read_catalog(ParseContext& ctx, const Element* root, Children& kids) {
  ctx.record_entities = false;
  const FileHeader header = parse_file_header(ctx, kids.one("FileHeader"));
  Catalog catalog = parse_catalog(ctx, kids.one("Catalog"));
  catalog.header = header;
  (void)root;
  return catalog;
}

ParameterValueDistribution read_distribution(ParseContext& ctx, Children& kids) {
  ctx.record_entities = false;
  const FileHeader header = parse_file_header(ctx, kids.one("FileHeader"));
  ParameterValueDistribution distribution =
      parse_parameter_value_distribution(ctx, kids.one("ParameterValueDistribution"));
  distribution.header = header;
  return distribution;
}

// Reads one document; every error found is thrown at the end, together.
template <class Body>
auto with_document(const XmlFile& xml, const LoadOptions& options, Diagnostics& diagnostics,
                   Body body) {
  ParseContext ctx(diagnostics, options);
  ctx.swap_file({xml.name, xml.directory, xml.text, xml.document.get()});
  warn_xml_repairs(ctx, xml);
  const Element* root = checked_root(ctx, xml);
  map_osc09_to_osc10(ctx, *xml.document);
  std::optional<decltype(body(ctx, root, std::declval<Children&>()))> result;
  ctx.recover([&] {
    Children kids(ctx, root, "OpenScenario");
    result.emplace(body(ctx, root, kids));
  });
  ctx.throw_errors();
  return std::move(*result);
}

void expect_kind(const XmlFile& xml, DocumentKind expected, const char* what) {
  const Element* root = xml.document->RootElement();
  if (std::string_view(root->Name()) == "OpenSCENARIO" && kind_of(root) != expected) {
    throw InputError(make_error(*xml.name, root->GetLineNum(),
                                std::string("this OpenSCENARIO document is not a ") + what));
  }
}

}  // namespace

Scenario parse_scenario(std::string_view text, const std::filesystem::path& path,
                        const LoadOptions& options, Diagnostics& diagnostics) {
  const XmlFile xml = parse_xml(text, path);
  expect_kind(xml, DocumentKind::kScenario, "scenario");
  return with_document(xml, options, diagnostics,
                       [&](ParseContext& ctx, const Element* root, Children& kids) {
                         return parse_scenario_root(ctx, root, kids, path);
                       });
}

Scenario load_scenario(const std::filesystem::path& path, const LoadOptions& options,
                       Diagnostics& diagnostics) {
  return parse_scenario(read_file(path), path, options, diagnostics);
}

Catalog load_catalog(const std::filesystem::path& path, Diagnostics& diagnostics) {
  const XmlFile xml = load_xml(path);
  expect_kind(xml, DocumentKind::kCatalog, "catalog");
  const LoadOptions options;
  return with_document(xml, options, diagnostics,
                       [&](ParseContext& ctx, const Element* root, Children& kids) {
                         return read_catalog(ctx, root, kids);
                       });
}

ParameterValueDistribution load_distribution(const std::filesystem::path& path,
                                             Diagnostics& diagnostics) {
  const XmlFile xml = load_xml(path);
  expect_kind(xml, DocumentKind::kDistribution, "parameter value distribution");
  const LoadOptions options;
  return with_document(xml, options, diagnostics,
                       [&](ParseContext& ctx, const Element*, Children& kids) {
                         return read_distribution(ctx, kids);
                       });
}

DocumentKind document_kind(const std::filesystem::path& path) {
  try {
    const std::string text = read_file(path);
    // Without the element's name anywhere in the text no parse can find a distribution: a plain
    // scenario (what `corsa run` is given) is then not parsed a second time just to say so.
    if (text.find("ParameterValueDistribution") == std::string::npos) {
      return DocumentKind::kScenario;
    }
    const XmlFile xml = parse_xml(text, path);
    const Element* root = xml.document->RootElement();
    if (std::string_view(root->Name()) != "OpenSCENARIO") return DocumentKind::kScenario;
    return kind_of(root);
  } catch (const InputError&) {
    return DocumentKind::kScenario;
  }
}

Document load_document(const std::filesystem::path& path, const LoadOptions& options,
                       Diagnostics& diagnostics) {
  return parse_document(read_file(path), path, options, diagnostics);
}

Document parse_document(std::string_view text, const std::filesystem::path& path,
                        const LoadOptions& options, Diagnostics& diagnostics) {
  const XmlFile xml = parse_xml(text, path);
  return with_document(xml, options, diagnostics,
                       [&](ParseContext& ctx, const Element* root, Children& kids) -> Document {
                         switch (kind_of(root)) {
                           case DocumentKind::kCatalog:
                             return read_catalog(ctx, root, kids);
                           case DocumentKind::kDistribution:
                             return read_distribution(ctx, kids);
                           case DocumentKind::kScenario:
                             break;
                         }
                         return parse_scenario_root(ctx, root, kids, path);
                       });
}

}  // namespace corsa::xosc
