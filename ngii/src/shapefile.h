#pragma once

// Thin RAII readers over shapelib for one layer: the .shp/.shx geometry and the .dbf attributes.
// Every failure becomes a corsa::InputError naming the file (and the record when one is at
// fault); shapelib's own error printing is silenced.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/ngii/layers.h"

namespace corsa::ngii::detail {

/// Geometry family a layer must have.
enum class ShapeFamily { kPoint, kPolyline, kPolygon };

/// Shapefile geometry (.shp with its .shx index).
class ShapeReader {
 public:
  /// Opens `shp` (its .shx must sit next to it); checks the shape type against `family`, and
  /// that every .shx entry points at the .shp record of its number with its length (a .shx of
  /// another file, or a damaged one, would pair shapes with the wrong attributes).
  ShapeReader(const std::filesystem::path& shp, ShapeFamily family);
  ShapeReader(const ShapeReader&) = delete;
  ShapeReader& operator=(const ShapeReader&) = delete;
  ~ShapeReader();

  int count() const { return count_; }
  /// True when the layer carries Z (PointZ / PolyLineZ).
  bool has_z() const { return has_z_; }
  /// Reads record `index` into `points` (all parts concatenated; `parts` receives their number).
  /// Returns false for a record without geometry (a null shape). Throws InputError naming the
  /// file and record for a truncated or corrupt record: one whose shape type is neither Null nor
  /// the layer's (the Shapefile specification requires one type for all non-Null shapes), or
  /// with a coordinate that is not a finite number.
  bool read(int index, std::vector<Point3>& points, int& parts) const;
  const std::string& file() const { return file_; }

 private:
  /// Throws InputError at the first .shx entry that disagrees with the .shp.
  void check_index(const std::filesystem::path& shx) const;

  void* handle_ = nullptr;  // SHPHandle, kept opaque so shapelib stays out of this header
  std::string file_;
  int count_ = 0;
  int type_ = 0;  // the layer's shape type from the header (SHPT_*)
  bool has_z_ = false;
};

/// DBF attributes. Field names are matched case-insensitively; text is returned as raw bytes
/// with the padding trimmed (the caller decodes CP949).
class DbfReader {
 public:
  explicit DbfReader(const std::filesystem::path& dbf);
  DbfReader(const DbfReader&) = delete;
  DbfReader& operator=(const DbfReader&) = delete;
  ~DbfReader();

  int count() const { return count_; }
  /// Index of a required field; throws InputError naming the file and listing the fields found.
  int require(std::string_view name) const;
  /// Index of an optional field, or -1.
  int find(std::string_view name) const;
  /// Raw text of a field, blanks trimmed ("" for NULL or a missing optional field, index < 0).
  std::string text(int record, int field) const;
  /// Integer value; nullopt for NULL/blank; throws InputError (file, record, field) for text
  /// that is not an integer.
  std::optional<int64_t> integer(int record, int field) const;
  /// Real value, same rules.
  std::optional<double> real(int record, int field) const;
  const std::string& file() const { return file_; }

 private:
  std::string field_name(int field) const;
  void* handle_ = nullptr;  // DBFHandle
  std::string file_;
  int count_ = 0;
  std::vector<std::string> names_;
};

}  // namespace corsa::ngii::detail
