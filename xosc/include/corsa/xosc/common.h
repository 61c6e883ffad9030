#pragma once

// Small types shared by every part of the OpenSCENARIO model: where an element came from, and the
// generic Properties / File / Range elements.

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"

namespace corsa::xosc {

/// Where an element was written: the file (as the user named it, or as resolved for catalogs)
/// and its 1-based line. Every model struct carries one so that the engine can report run-time
/// problems at the right place. The file name is shared between all elements of one file.
struct Source {
  std::shared_ptr<const std::string> file;
  int line = 0;

  const std::string& file_name() const;
  /// An error diagnostic located here.
  Diagnostic error(std::string message) const;
  Diagnostic warning(std::string message) const;
};

/// A name/value pair of a Properties element.
struct Property {
  std::string name;
  std::string value;
  Source source;
};

/// File: a path as written in the document (see also the resolved paths where the loader
/// resolves them, e.g. RoadNetwork::logic_file).
struct File {
  std::string filepath;
  Source source;
};

/// Properties: free name/value pairs, file references and custom XML content (kept as text).
struct Properties {
  std::vector<Property> properties;
  std::vector<File> files;
  std::vector<std::string> custom_content;
  Source source;

  /// The value of the first property called `name`, if any.
  std::optional<std::string> get(const std::string& name) const;
};

/// Range: closed interval [lower_limit, upper_limit] in the unit of the attribute it bounds.
struct Range {
  double lower_limit = 0.0;
  double upper_limit = 0.0;
  Source source;
};

/// License element of the FileHeader (1.2+).
struct License {
  std::string name;
  std::optional<std::string> resource;
  std::optional<std::string> spdx_id;
  std::string text;
  Source source;
};

/// FileHeader: OpenSCENARIO version and authoring data.
struct FileHeader {
  int rev_major = 1;
  int rev_minor = 0;
  std::string date;  ///< xsd:dateTime text as written
  std::string description;
  std::string author;
  std::optional<License> license;
  std::optional<Properties> properties;
  Source source;
};

}  // namespace corsa::xosc
