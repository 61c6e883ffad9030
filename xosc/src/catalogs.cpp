// Catalog lookup for CatalogReferences (§9.4) and catalog documents read on their own.

#include <algorithm>
#include <cstdlib>

#include "catalog_cache_impl.h"
#include "corsa/core/atomic_file.h"
#include "parsers.h"

namespace corsa::xosc {

CatalogOrigin parse_catalog_origin(ParseContext& ctx, const Element* reference) {
  Children kids(ctx, reference, "CatalogReference");
  CatalogOrigin origin;
  origin.catalog_name = ctx.req_str(reference, "catalogName");
  origin.entry_name = ctx.req_str(reference, "entryName");
  origin.assignments = parse_parameter_assignments(ctx, kids.opt("ParameterAssignments"));
  origin.reference = ctx.source(reference);
  return origin;
}

namespace {

// Why a catalog file listed without a document could not be read (it is read again: the error
// is only needed when a scenario needs an entry that may be in it).
Diagnostic unreadable_catalog_error(const XmlFile& file) {
  try {
    (void)load_xml(*file.name);
  } catch (const InputError& error) {
    return error.diagnostic();
  }
  return make_error(*file.name, 0, "could not be read while the catalogs were scanned");
}

// The children of a <Catalog> a scenario takes entries from, checked against the 1.3 schema
// (Catalog: a sequence of Vehicle, Controller, Pedestrian, MiscObject, Environment, Maneuver,
// Trajectory and Route) as any other element's are: an unknown element is an error at its line in
// the catalog file, whichever entry the scenario needs. Only the entries used are parsed.
void report_catalog_children(ParseContext& ctx, const XmlFile& file, const Element* catalog) {
  const ParseContext::FileState previous =
      ctx.swap_file({file.name, file.directory, file.text, file.document.get()});
  struct RestoreCatalogFile {
    ParseContext& ctx;
    const ParseContext::FileState& previous;
    ~RestoreCatalogFile() { ctx.swap_file(previous); }
  } restore{ctx, previous};
  Children kids(ctx, catalog, "Catalog");
  kids.consume_all();
}

}  // namespace

void CatalogResolver::scan(ParseContext& ctx) {
  scanned_ = true;
  const std::optional<CatalogDirectory>* directories[] = {
      &locations_.vehicle,     &locations_.controller,  &locations_.pedestrian,
      &locations_.misc_object, &locations_.environment, &locations_.maneuver,
      &locations_.trajectory,  &locations_.route};
  std::vector<std::filesystem::path> seen;
  for (const auto* directory : directories) {
    if (!directory->has_value()) continue;
    const std::filesystem::path& path = (*directory)->resolved;
    if (std::find(seen.begin(), seen.end(), path) != seen.end()) continue;
    seen.push_back(path);
    std::error_code error;
    if (!std::filesystem::is_directory(path, error)) {
      const Source& where = (*directory)->source;
      ctx.diagnostics().add_once(
          "catalog-dir:" + path.string(),
          make_warning(where.file_name(), where.line,
                       "catalog directory '" + (*directory)->path + "' does not exist"));
      continue;
    }
    // Parsed once per sweep when the load shares a CatalogCache, else read here.
    const std::shared_ptr<const CatalogFiles> files =
        ctx.options().catalog_cache
            ? ctx.options().catalog_cache->impl().directory(path)
            : std::make_shared<const CatalogFiles>(read_catalog_directory(path));
    for (const auto& xml : *files) {
      if (xml->document == nullptr) {
        Diagnostic warning = unreadable_catalog_error(*xml);
        warning.severity = Severity::kWarning;
        warning.message = "catalog file skipped: " + warning.message +
                          " (an error only for a scenario that needs an entry it may hold)";
        ctx.diagnostics().add_once("catalog-unreadable:" + *xml->name, warning);
        files_.push_back(xml);
        continue;
      }
      const Element* root = xml->document->RootElement();
      const Element* catalog = root->FirstChildElement("Catalog");
      if (catalog == nullptr) continue;  // not a catalog (a scenario kept next to them)
      const char* name = catalog->Attribute("name");
      if (name == nullptr) {
        throw InputError(
            make_error(*xml->name, catalog->GetLineNum(), "<Catalog> needs the attribute name"));
      }
      // Kept (and owned) even when its name repeats another file's: the lookup by directory may
      // still need it (esmini's environment catalog file calls itself VehicleCatalog).
      by_directory_[path].push_back(catalog);
      owners_[catalog] = xml.get();
      files_.push_back(xml);
      if (!catalogs_.emplace(name, catalog).second) {
        ctx.diagnostics().add_once(
            std::string("catalog-dup:") + name,
            make_warning(*xml->name, catalog->GetLineNum(),
                         std::string("catalog '") + name +
                             "' is defined in more than one file; using the first"));
      }
    }
  }
}

const Element* CatalogResolver::entry_of(const Element* catalog, const std::string& entry_name) {
  for (const Element* entry = catalog->FirstChildElement(); entry != nullptr;
       entry = entry->NextSiblingElement()) {
    const char* name = entry->Attribute("name");
    if (name != nullptr && entry_name == name) return entry;
  }
  return nullptr;
}

CatalogResolver::Hit CatalogResolver::found(ParseContext& ctx, const Element* catalog,
                                            const Element* entry) {
  const XmlFile* file = owners_.at(catalog);
  const std::filesystem::path path = *file->name;
  if (std::find(files_read_.begin(), files_read_.end(), path) == files_read_.end()) {
    files_read_.push_back(path);
    warn_xml_repairs(ctx, *file);
    report_catalog_children(ctx, *file, catalog);
  }
  return Hit{entry, file};
}

const std::optional<CatalogDirectory>* CatalogResolver::directory_for(std::string_view kind) const {
  if (kind == "Vehicle") return &locations_.vehicle;
  if (kind == "Controller") return &locations_.controller;
  if (kind == "Pedestrian") return &locations_.pedestrian;
  if (kind == "MiscObject") return &locations_.misc_object;
  if (kind == "Environment") return &locations_.environment;
  if (kind == "Maneuver") return &locations_.maneuver;
  if (kind == "Trajectory") return &locations_.trajectory;
  if (kind == "Route") return &locations_.route;
  return nullptr;
}

std::optional<std::string> CatalogResolver::file_lacking_entry(ParseContext& ctx,
                                                               const std::string& catalog_name,
                                                               const std::string& entry_name) {
  if (!scanned_) {
    scan(ctx);
  }
  for (const auto& file : files_) {
    if (file->document == nullptr) return std::nullopt;  // it may hold the entry
  }
  const auto named = catalogs_.find(catalog_name);
  if (named == catalogs_.end() || entry_of(named->second, entry_name) != nullptr) {
    return std::nullopt;
  }
  return *owners_.at(named->second)->name;
}

CatalogResolver::Hit CatalogResolver::find(ParseContext& ctx, const Element* reference,
                                           const std::string& catalog_name,
                                           const std::string& entry_name,
                                           std::initializer_list<std::string_view> kinds) {
  if (!scanned_) {
    scan(ctx);
  }
  // An entry not found may be in a catalog file that could not be read: its error is the cause.
  const auto fail_missing = [&](const std::string& message) {
    for (const auto& file : files_) {
      if (file->document != nullptr) continue;
      Diagnostic cause = unreadable_catalog_error(*file);
      cause.message += " (this catalog file may hold entry '" + clip(entry_name) +
                       "' of catalog '" + clip(catalog_name) + "', needed at " +
                       ctx.source(reference).file_name() + ":" +
                       std::to_string(ctx.source(reference).line) + ")";
      throw InputError(std::move(cause));
    }
    ctx.fail(reference, message);
  };
  const auto named = catalogs_.find(catalog_name);
  if (named != catalogs_.end()) {
    if (const Element* entry = entry_of(named->second, entry_name)) {
      return found(ctx, named->second, entry);
    }
    fail_missing("catalog '" + clip(catalog_name) + "' (" + *owners_.at(named->second)->name +
                 ") has no entry '" + clip(entry_name) + "'");
  }
  // No catalog of that name: a catalog file whose <Catalog name> differs from the name the
  // scenario uses (esmini finds entries by the directory of their kind).
  for (const auto kind : kinds) {
    const auto* directory = directory_for(kind);
    if (directory == nullptr || !directory->has_value()) continue;
    const auto catalogs = by_directory_.find((*directory)->resolved);
    if (catalogs == by_directory_.end()) continue;
    for (const Element* catalog : catalogs->second) {
      const Element* entry = entry_of(catalog, entry_name);
      if (entry == nullptr || std::string_view(entry->Name()) != kind) continue;
      ctx.lenient(reference, "no catalog file declares catalog '" + clip(catalog_name) + "'",
                  "catalog '" + std::string(catalog->Attribute("name")) + "' (" +
                      *owners_.at(catalog)->name + "), the " + std::string(kind) +
                      " catalog directory's one with entry '" + clip(entry_name) + "'");
      return found(ctx, catalog, entry);
    }
  }
  fail_missing("catalog '" + clip(catalog_name) + "' (for entry '" + clip(entry_name) +
               "') is not in any catalog directory of <CatalogLocations>");
  std::abort();  // fail_missing throws
}

Catalog parse_catalog(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Catalog");
  kids.consume_all();
  Catalog catalog;
  catalog.name = ctx.req_str(e, "name");
  const EntryScope scope{nullptr, true, "catalog entry"};
  std::set<std::string> names;
  for (const Element* entry = e->FirstChildElement(); entry != nullptr;
       entry = entry->NextSiblingElement()) {
    const std::string_view kind = entry->Name();
    const char* name = entry->Attribute("name");
    if (name != nullptr && !names.insert(name).second) {
      ctx.error(entry, "catalog entry name '" + clip(name) + "' is used twice");
    }
    ctx.recover([&] {
      if (kind == "Vehicle") catalog.vehicles.push_back(parse_vehicle(ctx, entry, scope));
      if (kind == "Controller") catalog.controllers.push_back(parse_controller(ctx, entry, scope));
      if (kind == "Pedestrian") catalog.pedestrians.push_back(parse_pedestrian(ctx, entry, scope));
      if (kind == "MiscObject") {
        catalog.misc_objects.push_back(parse_misc_object(ctx, entry, scope));
      }
      if (kind == "Environment") {
        catalog.environments.push_back(parse_environment(ctx, entry, scope));
      }
      if (kind == "Maneuver") catalog.maneuvers.push_back(parse_maneuver(ctx, entry, scope));
      if (kind == "Trajectory") {
        catalog.trajectories.push_back(parse_trajectory(ctx, entry, scope));
      }
      if (kind == "Route") catalog.routes.push_back(parse_route(ctx, entry, scope));
    });
  }
  catalog.source = ctx.source(e);
  return catalog;
}

}  // namespace corsa::xosc
