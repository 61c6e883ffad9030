#pragma once

// Internal: what a CatalogCache holds, and the listing of a catalog directory that loads share.

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "corsa/xosc/catalog_cache.h"
#include "parse_context.h"

namespace corsa::xosc {

using CatalogFiles = std::vector<std::shared_ptr<const XmlFile>>;

/// The .xosc files of a catalog directory, sorted by path, parsed. A file that cannot be read or
/// parsed is listed without a document (its error is found again when it matters, see
/// catalogs.cpp): one broken file must not fail every scenario using the directory.
CatalogFiles read_catalog_directory(const std::filesystem::path& directory);

struct CatalogCache::Impl {
  /// The parsed files of `directory`, read on first use. Every string of a cached document has
  /// been read once before it is shared: tinyxml2 decodes entities and whitespace in place on the
  /// first read, so only read-only documents may be used from several threads.
  std::shared_ptr<const CatalogFiles> directory(const std::filesystem::path& directory);

  mutable std::mutex mutex;
  std::map<std::filesystem::path, std::shared_ptr<const CatalogFiles>> directories;
};

}  // namespace corsa::xosc
