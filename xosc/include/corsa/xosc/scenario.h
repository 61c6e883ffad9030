#pragma once

// A loaded OpenSCENARIO scenario: read-only after load_scenario returns. Parameters are resolved,
// catalog references expanded, references checked, and the road network's LogicFile resolved to
// an absolute path (the map itself is loaded by the engine through corsa_xodr).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xosc/catalog_cache.h"
#include "corsa/xosc/catalogs.h"
#include "corsa/xosc/common.h"
#include "corsa/xosc/distributions.h"
#include "corsa/xosc/entities.h"
#include "corsa/xosc/parameters.h"
#include "corsa/xosc/storyboard.h"

namespace corsa::xosc {

struct TrafficSignalState {
  std::string traffic_signal_id;
  std::string state;
  Source source;
};
struct Phase {
  std::string name;
  double duration = 0.0;  ///< s
  std::vector<TrafficSignalState> states;
  std::optional<std::string> group_state;  ///< TrafficSignalGroupState (1.2)
  Source source;
};
struct TrafficSignalController {
  std::string name;
  std::optional<double> delay;           ///< s, relative to `reference`
  std::optional<std::string> reference;  ///< another controller's name
  std::vector<Phase> phases;
  Source source;
};

struct RoadNetwork {
  std::optional<File> logic_file;
  /// LogicFile resolved against the scenario file's folder (absolute, normalised); empty when
  /// there is no LogicFile.
  std::filesystem::path logic_file_path;
  std::optional<File> scene_graph_file;
  std::filesystem::path scene_graph_file_path;
  std::vector<TrafficSignalController> traffic_signal_controllers;
  std::vector<Position> used_area;
  Source source;
};

/// A position that names a road of the map (RoadPosition, LanePosition), as read: what a
/// RoadNetworkCheck looks up in the map.
struct RoadReference {
  const char* kind = "";  ///< element name, e.g. "LanePosition"
  std::string road_id;
  std::optional<std::string> lane_id;  ///< LanePosition's laneId, as written
  double s = 0.0;                      ///< m along the road
  Source source;
};

/// Checks the positions that name roads against the scenario's map while the scenario is read,
/// so that `corsa validate` reports them with the document's other errors in one pass. corsa_xosc
/// reads no maps: the engine implements this (corsa/engine/road_network_check.h).
class RoadNetworkCheck {
 public:
  virtual ~RoadNetworkCheck() = default;
  /// The errors of `references` against the map `network` names (each at its reference; the
  /// map's own errors when it does not load). Warnings go to `diagnostics`.
  virtual std::vector<Diagnostic> check(const RoadNetwork& network,
                                        const std::vector<RoadReference>& references,
                                        Diagnostics& diagnostics) const = 0;
};

struct Scenario {
  FileHeader header;
  std::filesystem::path path;                    ///< the .xosc as given to load_scenario
  std::vector<ParameterDeclaration> parameters;  ///< global, with overrides applied
  std::vector<VariableDeclaration> variables;
  std::vector<MonitorDeclaration> monitors;
  CatalogLocations catalog_locations;
  RoadNetwork road_network;
  Entities entities;
  Storyboard storyboard;
  /// Every catalog file read while expanding references, in the order first read.
  std::vector<std::filesystem::path> catalog_files;
  Source source;

  const ParameterDeclaration* find_parameter(const std::string& name) const;
  const VariableDeclaration* find_variable(const std::string& name) const;
};

struct LoadOptions {
  /// Values for global parameters from outside (`--param name=value`), in order. Each must name
  /// a declared global parameter and be valid for its type; it replaces the declared value.
  std::vector<std::pair<std::string, std::string>> parameters;
  /// Check that the LogicFile exists (an error when not). Off for fuzzing.
  bool check_files = true;
  /// Lenient readings (a rule of the standard broken in a way whose meaning is clear, read as
  /// its author meant with a `(read as ...)` warning) become errors (`--strict`).
  bool strict = false;
  /// A boolean written in another case than the schema's (`True`, `FALSE`) is true only as
  /// esmini's reader has it: its text must be `true` or `1`, so `True` reads false (the run's
  /// `--semantics esmini`). Off: the author's evident meaning, `True` true (a lenient reading).
  bool esmini_booleans = false;
  /// Catalog files parsed once and shared between loads (sweeps); null: each load reads them.
  std::shared_ptr<CatalogCache> catalog_cache;
  /// Checks road and lane references against the map while loading (`corsa validate`); null:
  /// the engine checks each position when it places something there.
  std::shared_ptr<const RoadNetworkCheck> road_network_check;
};

/// Thrown by load_scenario when the only errors are values given from outside (LoadOptions::
/// parameters, a catalog reference's assignments) that violate their declarations' value
/// constraints: the document is fine, that combination of values is not one it allows (a sweep
/// skips such variants, as the ASAM ALKS variation files expect).
class ConstraintViolation : public InputError {
 public:
  explicit ConstraintViolation(std::vector<Diagnostic> diagnostics)
      : InputError(std::move(diagnostics)) {}
};

/// Loads a scenario file. Throws one InputError holding every error found (file:line: message,
/// in the order found); warnings (deprecated spellings, unsupported optional features, lenient
/// readings) go to `diagnostics`.
Scenario load_scenario(const std::filesystem::path& path, const LoadOptions& options,
                       Diagnostics& diagnostics);

/// Same, from text in memory; `path` names the file for messages and relative paths.
Scenario parse_scenario(std::string_view xml, const std::filesystem::path& path,
                        const LoadOptions& options, Diagnostics& diagnostics);

/// What an .xosc file holds, by its content (scenario, catalog, or parameter distribution).
enum class DocumentKind { kScenario, kCatalog, kDistribution };
using Document = std::variant<Scenario, Catalog, ParameterValueDistribution>;

/// The kind of the OpenSCENARIO document in a file, by the element after its FileHeader;
/// kScenario for a file that cannot be read or parsed, or is no OpenSCENARIO document (loading it
/// as a scenario then reports why).
DocumentKind document_kind(const std::filesystem::path& path);

/// Loads any OpenSCENARIO document, deciding its kind from the element after FileHeader.
Document load_document(const std::filesystem::path& path, const LoadOptions& options,
                       Diagnostics& diagnostics);

/// Same, from text in memory; `path` names the file for messages and relative paths.
Document parse_document(std::string_view xml, const std::filesystem::path& path,
                        const LoadOptions& options, Diagnostics& diagnostics);

}  // namespace corsa::xosc
