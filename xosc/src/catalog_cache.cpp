// CatalogCache: parsed catalog directories shared between scenario loads (catalog_cache.h).

#include <algorithm>

#include "catalog_cache_impl.h"
#include "osc09_mapping.h"

namespace corsa::xosc {
namespace {

// Reads every lazily decoded string of the document once (see CatalogCache::Impl).
void settle(const tinyxml2::XMLNode* node) {
  for (; node != nullptr; node = node->NextSibling()) {
    (void)node->Value();
    if (const tinyxml2::XMLElement* element = node->ToElement()) {
      for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr;
           a = a->Next()) {
        (void)a->Name();
        (void)a->Value();
      }
    }
    settle(node->FirstChild());
  }
}

}  // namespace

CatalogFiles read_catalog_directory(const std::filesystem::path& directory) {
  // Sorted, so that which file wins a duplicated catalog name does not depend on the file
  // system's listing order.
  std::vector<std::filesystem::path> paths;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xosc") {
      paths.push_back(entry.path());
    }
  }
  std::sort(paths.begin(), paths.end());
  CatalogFiles files;
  for (const auto& path : paths) {
    try {
      XmlFile file = load_xml(path);
      map_osc09_catalog_file(file);
      files.push_back(std::make_shared<const XmlFile>(std::move(file)));
    } catch (const InputError&) {
      // Kept without a document: a scenario that needs none of its entries still runs
      // (CatalogResolver warns, and fails with this file's error only when an entry is missing).
      XmlFile unreadable;
      unreadable.name = std::make_shared<const std::string>(path.string());
      unreadable.directory = std::filesystem::absolute(path).parent_path();
      files.push_back(std::make_shared<const XmlFile>(std::move(unreadable)));
    }
  }
  return files;
}

std::shared_ptr<const CatalogFiles> CatalogCache::Impl::directory(
    const std::filesystem::path& path) {
  std::lock_guard lock(mutex);
  const auto found = directories.find(path);
  if (found != directories.end()) {
    return found->second;
  }
  auto files = std::make_shared<const CatalogFiles>(read_catalog_directory(path));
  for (const auto& file : *files) {
    settle(file->document.get());
  }
  directories.emplace(path, files);
  return files;
}

CatalogCache::CatalogCache() : impl_(std::make_unique<Impl>()) {}
CatalogCache::~CatalogCache() = default;

size_t CatalogCache::file_count() const {
  std::lock_guard lock(impl_->mutex);
  size_t count = 0;
  for (const auto& [path, files] : impl_->directories) count += files->size();
  return count;
}

}  // namespace corsa::xosc
