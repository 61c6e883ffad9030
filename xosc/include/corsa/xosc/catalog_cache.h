#pragma once

// Catalog files parsed once and shared, read-only, between loads of scenarios. A parameter sweep
// loads one scenario thousands of times with different parameter values; parameters are
// resolved while catalog entries are expanded, so what loads can share is the catalog files'
// parsed XML (§9.4 catalogs), not the expanded entries.

#include <cstddef>
#include <memory>

namespace corsa::xosc {

/// Pass one cache in LoadOptions::catalog_cache to every load that should share it. Thread-safe:
/// loads on several threads may use one cache. A catalog directory is read when a load first
/// needs it; later changes to its files are not seen by loads using this cache.
class CatalogCache {
 public:
  CatalogCache();
  ~CatalogCache();
  CatalogCache(const CatalogCache&) = delete;
  CatalogCache& operator=(const CatalogCache&) = delete;

  /// Catalog files parsed so far.
  size_t file_count() const;

  struct Impl;  ///< corsa_xosc's own (catalog_cache_impl.h)
  Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace corsa::xosc
