#pragma once

// Internal: the state of one load. Reads attributes with `$parameter` and `${expression}`
// resolution, keeps the parameter scopes, checks children against the schema table, and records
// the references that are checked once the whole document is read.

#include <tinyxml2.h>

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/xosc/common.h"
#include "corsa/xosc/parameters.h"
#include "corsa/xosc/scenario.h"
#include "enum_tables.h"
#include "xml_attributes.h"

namespace corsa::xosc {

using Element = tinyxml2::XMLElement;

class CatalogResolver;

/// Thrown once a document has so many errors that reading on is pointless; it holds them all
/// and passes every recover().
class TooManyErrors : public InputError {
 public:
  explicit TooManyErrors(std::vector<Diagnostic> diagnostics)
      : InputError(std::move(diagnostics)) {}
};

/// A parsed XML file and the name its elements report.
struct XmlFile {
  std::unique_ptr<tinyxml2::XMLDocument> document;
  std::shared_ptr<const std::string> name;
  std::filesystem::path directory;  ///< folder relative paths in the file are resolved against
  /// The text the document was parsed from (its DOCTYPE's entities expanded, repairs made), for
  /// the lines of attributes in errors (ParseContext::attribute_line).
  std::shared_ptr<const std::string> text;
  /// Attributes written twice in a tag, read as their first value (XML 1.0 §3.1 forbids the
  /// repeat); whoever reads the document warns about them (warn_xml_repairs).
  std::vector<RepeatedAttribute> repeated_attributes;
  /// Line of an XML declaration that follows comments instead of opening the file (XML 1.0
  /// §2.8 allows it only at the very start), read as if it opened the file; 0 when none.
  int late_declaration_line = 0;
  /// What the 0.9-to-1.0 mapping read leniently (`read_as` set) or found in error in a 0.9
  /// catalog file, mapped once when the file was read (catalog files are shared between loads);
  /// whoever reads the document reports them (warn_xml_repairs).
  struct MappingNote {
    Source where;
    std::string message;
    std::optional<std::string> read_as;  ///< nullopt: an error
  };
  std::vector<MappingNote> mapping_notes;
};

/// Parses XML text; throws InputError "malformed XML: ..." at the offending line.
XmlFile parse_xml(std::string_view text, const std::filesystem::path& path);
/// Reads and parses a file (InputError when it cannot be read).
XmlFile load_xml(const std::filesystem::path& path);

class ParseContext;

/// Where an attribute is written, found only when asked: the file's text is scanned then
/// (error paths), not when the element is read.
struct DeferredAttributeLine {
  std::shared_ptr<const std::string> text;  ///< null: the tag's line is the answer
  int tag_line = 0;
  int ordinal = 0;  ///< start tags before the element's on its line
  std::string name;
  int line() const;
};
/// The lenient-reading warnings (errors under --strict) for what parse_xml repaired in `file`:
/// each repeated attribute, a late XML declaration.
void warn_xml_repairs(ParseContext& ctx, const XmlFile& file);

/// A use of an entity name, checked after the Entities are known.
struct EntityUse {
  std::string name;
  Source source;
  std::string what;  ///< e.g. "entityRef"
};

class ParseContext {
 public:
  ParseContext(Diagnostics& diagnostics, const LoadOptions& options);

  Diagnostics& diagnostics() { return diagnostics_; }
  const LoadOptions& options() const { return options_; }

  // --- location -------------------------------------------------------------------------------
  Source source(const Element* element) const;
  /// An error that leaves nothing sensible to read of the element: throws, and the nearest
  /// recover() records it and goes on with the next element.
  [[noreturn]] void fail(const Element* element, std::string message) const;
  /// An error after which reading can go on (a bad value, an unknown child): recorded, so that
  /// one pass reports every error of a document.
  void error(const Element* element, std::string message);
  /// An error about attribute `name` of `element`, at the attribute's own line.
  void attribute_error(const Element* element, std::string_view name, std::string message);
  /// The line attribute `name` of `element` is written on: the element's line unless its tag
  /// runs over several lines (then found in the file's text; error paths only).
  int attribute_line(const Element* element, std::string_view name) const;
  /// attribute_line() put off until DeferredAttributeLine::line() is called.
  DeferredAttributeLine defer_attribute_line(const Element* element, std::string_view name) const;
  /// As error(), at `line` of the element's file (a text node's, say) instead of the element's.
  void error_at_line(const Element* element, int line, std::string message);
  /// Records the diagnostics of a caught InputError (once each).
  void record(const InputError& error);
  /// Runs `body`; an InputError it throws is recorded and false returned. Placed around each
  /// element of a list, so that one bad element does not hide the errors of the next.
  template <class Body>
  bool recover(Body&& body) {
    try {
      body();
      return true;
    } catch (const TooManyErrors&) {
      throw;
    } catch (const InputError& caught) {
      record(caught);
      return false;
    }
  }
  /// The errors recorded so far, in the order found.
  const std::vector<Diagnostic>& errors() const { return errors_; }
  /// Throws every recorded error as one InputError, if there are any.
  void throw_errors() const;
  void warn_once(const Element* element, const std::string& key, std::string message);
  /// A rule of the standard broken in a way whose meaning is clear (the liberal reading of
  /// docs/openscenario.md "Lenient reading"): warns `message (read as read_as)` once per place,
  /// or, with LoadOptions::strict, records it as an error.
  void lenient(const Element* element, std::string_view message, std::string_view read_as);
  void lenient(const Source& where, std::string_view message, std::string_view read_as);
  /// A lenient reading a run makes only when it meets this element (the engine's words at the
  /// run's place): warned about (an error when strict) by a load that checks the document
  /// against its map too (LoadOptions::road_network_check, `corsa validate`), which is the load
  /// that stands for a run; run and sweep leave it to the run.
  void run_reading(const Source& where, std::string_view message, std::string_view read_as) {
    if (options_.road_network_check) lenient(where, message, read_as);
  }
  /// A deprecated 1.0/1.1 spelling: one warning per spelling.
  void deprecated(const Element* element, std::string_view what, std::string_view instead);

  /// The file and folder elements are read from (switched while expanding catalogs).
  struct FileState {
    std::shared_ptr<const std::string> name;
    std::filesystem::path directory;
    std::shared_ptr<const std::string> text;          ///< XmlFile::text
    const tinyxml2::XMLDocument* document = nullptr;  ///< the document parsed from `text`
  };
  const FileState& file() const { return file_; }
  FileState swap_file(FileState file);

  // --- attributes (resolved) ------------------------------------------------------------------
  std::optional<std::string> attr(const Element* element, const char* name);
  std::string req_str(const Element* element, const char* name);
  std::optional<std::string> opt_str(const Element* element, const char* name);
  double req_double(const Element* element, const char* name);
  std::optional<double> opt_double(const Element* element, const char* name);
  int64_t req_int(const Element* element, const char* name,
                  ParameterType type = ParameterType::kInt);
  std::optional<int64_t> opt_int(const Element* element, const char* name,
                                 ParameterType type = ParameterType::kInt);
  bool req_bool(const Element* element, const char* name);
  std::optional<bool> opt_bool(const Element* element, const char* name);

  /// `text` as a value of `type` (`what` names it in messages); an integer written with a zero
  /// fraction ("-5.0") is read leniently. nullopt when it is not one.
  std::optional<Value> typed_value(const Element* element, ParameterType type,
                                   std::string_view text, std::string_view what);

  template <class E>
  std::optional<E> opt_enum(const Element* element, const char* name) {
    const auto text = attr(element, name);
    if (!text) {
      return std::nullopt;
    }
    if (failed_) return E{};
    const EnumEntry<E>* entry = find_enum<E>(*text);
    if (entry == nullptr) {
      attribute_error(element, name,
                      "attribute " + std::string(name) + ": '" + clip(*text) + "' is not a valid " +
                          std::string(enum_type_name<E>()));
      return E{};
    }
    if (entry->deprecated) {
      deprecated(element, std::string(enum_type_name<E>()) + " value '" + *text + "'",
                 entry->replacement.empty() ? std::string_view{} : entry->replacement);
    }
    return entry->value;
  }
  template <class E>
  E req_enum(const Element* element, const char* name) {
    const auto value = opt_enum<E>(element, name);
    if (!value) {
      missing(element, name);
    }
    return *value;
  }
  [[noreturn]] void missing(const Element* element, const char* name) const;
  /// An attribute that names a parameter or variable (parameterRef, variableRef): taken as
  /// written, not resolved; a leading `$` (some writers add it) is dropped.
  std::string parameter_name(const Element* element, const char* name) const;

  /// Resolves `$name` and `${expr}` in `text` against the visible parameters; other text is
  /// returned as is.
  std::string resolve(const Element* element, const std::string& text);

  // --- parameters -----------------------------------------------------------------------------
  /// Opens a scope with the declarations of `declarations` (a ParameterDeclarations element, or
  /// null for an empty scope), applying `overrides` (already resolved values), resolves them and
  /// returns them. `isolated` hides all outer scopes (catalog entries).
  std::vector<ParameterDeclaration> push_scope(const Element* declarations,
                                               const std::vector<ParameterAssignment>& overrides,
                                               bool isolated, std::string_view owner);
  void pop_scope();
  bool parameter_visible(const std::string& name);

  // --- references -----------------------------------------------------------------------------
  void use_entity(const Element* element, const std::string& name, std::string what);
  std::vector<EntityUse>& entity_uses() { return entity_uses_; }
  /// A position naming a road, for LoadOptions::road_network_check.
  void use_road(RoadReference reference) { road_uses_.push_back(std::move(reference)); }
  const std::vector<RoadReference>& road_uses() const { return road_uses_; }
  /// Entity, parameter, variable and monitor references are checked only while this is set
  /// (in a scenario, not in a catalog or distribution read on its own).
  bool record_entities = true;
  /// Fails unless `name` is a visible or global parameter (ParameterSetAction, ...).
  void check_parameter_ref(const Element* element, const std::string& name);
  void check_variable_ref(const Element* element, const std::string& name);
  /// The type of a visible (or global) parameter / of a declared variable; nullopt when unknown.
  std::optional<ParameterType> parameter_type(const std::string& name);
  std::optional<ParameterType> variable_type(const std::string& name) const;
  void check_monitor_ref(const Element* element, const std::string& name);

  /// RoadNetwork/TrafficSignals: controller name -> its phase names.
  std::map<std::string, std::vector<std::string>> signal_controllers;
  /// Warns when a TrafficSignalController action or condition names an undeclared controller
  /// or phase (a warning: a simulator may know controllers from elsewhere).
  void check_signal_controller(const Element* element, const std::string& controller,
                               const std::string& phase);
  /// CARLA evaluation criteria met in triggers (left out), with their condition names:
  /// report_carla_criteria warns once per file for them.
  std::vector<std::pair<Source, std::string>> carla_criteria;
  std::set<std::string> global_parameters;         ///< names of the scenario's global parameters
  std::map<std::string, ParameterType> variables;  ///< declared VariableDeclarations, by name
  std::set<std::string> monitors;                  ///< declared MonitorDeclarations names
  /// Entities whose definition had errors (reported): references to them are not errors too.
  std::set<std::string> unreadable_entities;
  CatalogResolver* catalogs = nullptr;
  /// Where each StoryboardElementStateCondition's storyboardElementRef is written, by the
  /// condition's file and tag line and the reference: an unknown or ambiguous reference, found
  /// once the storyboard is read, is reported at the attribute's own line.
  std::map<std::tuple<const std::string*, int, std::string>, DeferredAttributeLine> storyboard_refs;

 private:
  struct Entry {
    ParameterDeclaration declaration;
    const Element* element = nullptr;
    bool literal = false;  ///< value given from outside: parse only, do not resolve `$`
    /// The value could not be read (reported at the declaration): each use is an error.
    bool in_error = false;
    Source value_source;  ///< where the effective value was written
    enum class State { kPending, kResolving, kDone } state = State::kPending;
    std::vector<const Element*> constraint_elements;  ///< ValueConstraint elements, in order
  };
  struct Scope {
    std::vector<Entry> entries;
    size_t barrier = 0;  ///< first scope index visible from this one
  };

  /// The visible entry called `name`, resolved; null when there is none.
  const Entry* lookup(std::string_view name, size_t upto, const Element* from);
  /// The error at a use of `entry`, whose value is in error.
  std::string unusable_message(const Entry& entry) const;
  /// attr() without the bookkeeping: nullopt when absent; `failed_` set when the value could
  /// not be resolved (the error is recorded).
  std::optional<std::string> resolved(const Element* element, const char* name);
  Entry read_declaration(const Element* element);
  void resolve_entry(size_t scope, size_t index);
  void check_constraints(Entry& entry);
  std::string resolve_in(const Element* element, const std::string& text, size_t upto);

  Diagnostics& diagnostics_;
  const LoadOptions& options_;
  FileState file_;
  std::vector<Scope> scopes_;
  std::vector<std::string> resolving_;  ///< chain of parameters being resolved (cycle message)
  std::vector<EntityUse> entity_uses_;
  std::vector<RoadReference> road_uses_;
  std::vector<Diagnostic> errors_;
  /// Indices in errors_ of value-constraint violations by values from outside (LoadOptions,
  /// catalog assignments): when they are all the errors, the document itself is fine.
  std::vector<size_t> outside_violations_;
  /// Set when the last attribute read could not be resolved (its error is recorded): the typed
  /// readers then return a neutral value without a second error for the same attribute.
  bool failed_ = false;
};

/// Thrown to leave an element whose error was recorded already (recover() does not record it
/// again).
class RecordedError : public InputError {
 public:
  explicit RecordedError(Diagnostic diagnostic) : InputError(std::move(diagnostic)) {}
};

/// Opens a parameter scope for the lifetime of the guard.
class ScopeGuard {
 public:
  explicit ScopeGuard(ParseContext& context) : context_(context) {}
  ScopeGuard(const ScopeGuard&) = delete;
  ScopeGuard& operator=(const ScopeGuard&) = delete;
  ~ScopeGuard() { context_.pop_scope(); }

 private:
  ParseContext& context_;
};

/// The children of one element, checked against the schema rule of its XSD type: unknown
/// children are errors, unknown attributes warnings. Accessors take children by name.
class Children {
 public:
  Children(ParseContext& context, const Element* element, std::string_view type);
  Children(const Children&) = delete;
  Children& operator=(const Children&) = delete;
  /// Warns about children the parse function never asked for (a gap in Corsa, not in the file),
  /// so that nothing in a document is dropped silently.
  ~Children();
  /// For parse functions that walk the children themselves.
  void consume_all() { consumed_all_ = true; }

  const Element* element() const { return element_; }
  /// Exactly one child called `name`.
  const Element* one(const char* name);
  /// At most one.
  const Element* opt(const char* name);
  /// Any number, in document order.
  std::vector<const Element*> all(const char* name);
  /// At least `minimum`.
  std::vector<const Element*> at_least(const char* name, size_t minimum);
  /// The single child of a choice element (exactly one child, of a name the type allows).
  const Element* choice();

 private:
  void consumed(std::string_view name);

  ParseContext& context_;
  const Element* element_;
  std::string_view type_;
  std::vector<std::string_view> consumed_;
  bool consumed_all_ = false;
};

/// Reads a child beyond what its parent allows (its cardinality error is reported by Children)
/// for the errors inside it; the result is dropped.
void read_extra_child(ParseContext& ctx, const Element* element);

/// Text content of an element ("" when none).
std::string element_text(const Element* element);
/// "int", "double", ... as the schema spells the type.
std::string type_name(ParameterType type);
/// `OpenSCENARIO/Storyboard/Init` for messages.
std::string element_path(const Element* element);

}  // namespace corsa::xosc
