#pragma once

// Internal: finds catalog entries for CatalogReferences, reading the catalog files of the
// scenario's CatalogLocations once, and expands them (template in this header).

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parse_context.h"

namespace corsa::xosc {

class CatalogResolver {
 public:
  explicit CatalogResolver(const CatalogLocations& locations) : locations_(locations) {}

  struct Hit {
    const Element* entry = nullptr;
    const XmlFile* file = nullptr;
  };
  /// The entry `entry_name` of catalog `catalog_name`; fails at `reference` naming both when the
  /// catalog or the entry does not exist. When no catalog file declares `catalog_name` but a
  /// catalog in the directory given for the entry's kinds (`kinds`, e.g. "Vehicle") has the
  /// entry, that one is taken with a lenient-reading warning (esmini looks there too).
  Hit find(ParseContext& ctx, const Element* reference, const std::string& catalog_name,
           const std::string& entry_name, std::initializer_list<std::string_view> kinds);

  /// The file of catalog `catalog_name` when that catalog is at hand, every catalog file could
  /// be read, and it has no entry `entry_name`; nullopt otherwise (found, or a failure find()
  /// reports with its cause).
  std::optional<std::string> file_lacking_entry(ParseContext& ctx, const std::string& catalog_name,
                                                const std::string& entry_name);

  const std::vector<std::filesystem::path>& files_read() const { return files_read_; }

  /// Catalog entries being expanded (to stop self-reference).
  std::vector<std::string> expanding;
  /// Expansions so far: entries referencing other entries several times could otherwise grow
  /// exponentially; past kMaxExpansions the load fails instead of hanging.
  size_t expansions = 0;
  static constexpr size_t kMaxExpansions = 10000;

 private:
  void scan(ParseContext& ctx);
  const Element* entry_of(const Element* catalog, const std::string& entry_name);
  Hit found(ParseContext& ctx, const Element* catalog, const Element* entry);
  /// The catalog directory CatalogLocations gives for entries of kind `kind`, if any.
  const std::optional<CatalogDirectory>* directory_for(std::string_view kind) const;

  const CatalogLocations& locations_;
  bool scanned_ = false;
  std::vector<std::shared_ptr<const XmlFile>> files_;
  std::map<std::string, const Element*> catalogs_;  // catalog name -> Catalog element
  std::map<const Element*, const XmlFile*> owners_;
  std::map<std::filesystem::path, std::vector<const Element*>> by_directory_;
  std::vector<std::filesystem::path> files_read_;
};

/// Reads the catalogName / entryName / ParameterAssignments of a CatalogReference.
CatalogOrigin parse_catalog_origin(ParseContext& ctx, const Element* reference);

template <class T, class Parse>
T expand_catalog_reference(ParseContext& ctx, const Element* reference,
                           std::initializer_list<std::string_view> kinds, Parse parse) {
  CatalogOrigin origin = parse_catalog_origin(ctx, reference);
  if (ctx.catalogs == nullptr) {
    ctx.warn_once(reference, "catalog-outside-scenario",
                  "catalog references inside a catalog are checked only when a scenario uses "
                  "the entry");
    T value{};
    if constexpr (requires { value.catalog; }) {
      value.catalog = std::move(origin);
    }
    return value;
  }
  const std::string key = origin.catalog_name + "/" + origin.entry_name;
  for (const auto& open : ctx.catalogs->expanding) {
    if (open == key) {
      ctx.fail(reference, "catalog entry '" + origin.entry_name + "' of catalog '" +
                              origin.catalog_name + "' references itself");
    }
  }
  const CatalogResolver::Hit hit =
      ctx.catalogs->find(ctx, reference, origin.catalog_name, origin.entry_name, kinds);
  bool kind_ok = false;
  std::string expected;
  for (const auto kind : kinds) {
    kind_ok = kind_ok || kind == hit.entry->Name();
    expected += (expected.empty() ? "" : " or ") + std::string(kind);
  }
  if (!kind_ok) {
    ctx.fail(reference, "catalog entry '" + origin.entry_name + "' of catalog '" +
                            origin.catalog_name + "' is a " + hit.entry->Name() + ", expected " +
                            expected);
  }
  if (++ctx.catalogs->expansions > CatalogResolver::kMaxExpansions) {
    ctx.fail(reference, "more than " + std::to_string(CatalogResolver::kMaxExpansions) +
                            " catalog references expanded; do catalog entries reference each "
                            "other in a loop?");
  }
  // Restored however the entry's parse ends: an error in it is recorded and reading goes on
  // in the referencing file.
  struct Restore {
    ParseContext& ctx;
    ParseContext::FileState previous;
    bool record;
    ~Restore() {
      ctx.record_entities = record;
      ctx.swap_file(previous);
      ctx.catalogs->expanding.pop_back();
    }
  };
  ctx.catalogs->expanding.push_back(key);
  const Restore restore{ctx,
                        ctx.swap_file({hit.file->name, hit.file->directory, hit.file->text,
                                       hit.file->document.get()}),
                        ctx.record_entities};
  return parse(hit.entry, origin);
}

}  // namespace corsa::xosc
