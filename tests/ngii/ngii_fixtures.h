#pragma once

// Shared helpers of the NGII tests: where the real areas are, and byte-level edits of copies of
// their files (to build bad inputs without any Shapefile library in the test).

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace corsa::test {

inline std::filesystem::path ngii_area(const std::string& name) {
  return std::filesystem::path(CORSA_SHARED_DIR) / "data" / "ngii" / name;
}

/// Copies every file of `area` whose name starts with one of `layers` into `dir`.
inline void copy_layers(const std::filesystem::path& area, const std::filesystem::path& dir,
                        const std::vector<std::string>& layers) {
  for (const auto& entry : std::filesystem::directory_iterator(area)) {
    const std::string name = entry.path().filename().string();
    for (const auto& layer : layers) {
      if (name.rfind(layer + ".", 0) == 0) {
        std::filesystem::copy_file(entry.path(), dir / name);
        std::filesystem::permissions(dir / name, std::filesystem::perms::owner_write,
                                     std::filesystem::perm_options::add);
      }
    }
  }
}

inline std::vector<char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// A dBASE III field descriptor: name, offset of its value inside a record, width.
struct DbfField {
  std::string name;
  size_t offset = 0;
  size_t width = 0;
  size_t descriptor = 0;  ///< byte position of the descriptor in the file
};

inline uint16_t le16(const std::vector<char>& b, size_t at) {
  return static_cast<uint16_t>(static_cast<unsigned char>(b[at]) |
                               (static_cast<unsigned char>(b[at + 1]) << 8));
}

inline std::vector<DbfField> dbf_fields(const std::vector<char>& bytes) {
  std::vector<DbfField> fields;
  size_t offset = 1;  // each record starts with the deletion flag
  for (size_t at = 32; at + 32 <= bytes.size() && bytes[at] != 0x0D; at += 32) {
    DbfField field;
    field.name = std::string(&bytes[at], strnlen(&bytes[at], 11));
    field.width = static_cast<unsigned char>(bytes[at + 16]);
    field.offset = offset;
    field.descriptor = at;
    offset += field.width;
    fields.push_back(field);
  }
  return fields;
}

/// Overwrites one text field of one record (space padded, like dBASE).
inline void set_dbf_text(const std::filesystem::path& path, int record, const std::string& name,
                         const std::string& value) {
  std::vector<char> bytes = read_bytes(path);
  const size_t header = le16(bytes, 8);
  const size_t record_size = le16(bytes, 10);
  for (const DbfField& field : dbf_fields(bytes)) {
    if (field.name == name) {
      std::string padded = value;
      padded.resize(field.width, ' ');
      std::memcpy(&bytes[header + record_size * static_cast<size_t>(record) + field.offset],
                  padded.data(), field.width);
      write_bytes(path, bytes);
      return;
    }
  }
  throw std::runtime_error("no field " + name);
}

/// Renames a field in the header (same or shorter name).
inline void rename_dbf_field(const std::filesystem::path& path, const std::string& name,
                             const std::string& new_name) {
  std::vector<char> bytes = read_bytes(path);
  for (const DbfField& field : dbf_fields(bytes)) {
    if (field.name == name) {
      std::memset(&bytes[field.descriptor], 0, 11);
      std::memcpy(&bytes[field.descriptor], new_name.data(), new_name.size());
      write_bytes(path, bytes);
      return;
    }
  }
  throw std::runtime_error("no field " + name);
}

inline void truncate_file(const std::filesystem::path& path, size_t size) {
  std::vector<char> bytes = read_bytes(path);
  bytes.resize(size);
  write_bytes(path, bytes);
}

}  // namespace corsa::test
