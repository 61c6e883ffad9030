#include "shapefile.h"

#include <fcntl.h>
#include <shapefil.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "corsa/core/input_file.h"
#include "corsa/core/strings.h"

namespace corsa::ngii::detail {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& file, int64_t record, std::string message) {
  Diagnostic diagnostic = make_error(file, 0, std::move(message));
  diagnostic.record = record;
  throw InputError(std::move(diagnostic));
}

// shapelib opens "<base>.shp" / ".shx" / ".dbf" itself, trying only lower and upper case
// extensions; this hook also finds e.g. "A2_LINK.Shx" by a case-insensitive directory scan.
// It returns a FILE* like shapelib's default hook, so the default read/seek/close hooks apply.
// Only regular files are opened (fopen would block on a FIFO); the readers check them first to
// say why (check_input_file), this keeps a file swapped in meanwhile from blocking.
std::FILE* open_regular(const char* name, const char* access) {
  const int fd = ::open(name, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    return nullptr;
  }
  struct stat status {};
  std::FILE* file = nullptr;
  if (::fstat(fd, &status) == 0 && S_ISREG(status.st_mode)) {
    file = ::fdopen(fd, access);
  } else {
    errno = EINVAL;
  }
  if (file == nullptr) {
    ::close(fd);
  }
  return file;
}

SAFile open_case_insensitive(const char* name, const char* access) {
  if (std::FILE* file = open_regular(name, access)) {
    return reinterpret_cast<SAFile>(file);
  }
  if (errno != ENOENT) {
    return nullptr;
  }
  const fs::path wanted(name);
  std::error_code error;
  const fs::path dir = wanted.has_parent_path() ? wanted.parent_path() : fs::path(".");
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    if (iequals(entry.path().filename().string(), wanted.filename().string())) {
      return reinterpret_cast<SAFile>(open_regular(entry.path().c_str(), access));
    }
  }
  return nullptr;
}

void silent_error(const char* /*message*/) {}

SAHooks make_hooks() {
  SAHooks hooks;
  SASetupDefaultHooks(&hooks);
  hooks.FOpen = open_case_insensitive;
  hooks.Error = silent_error;
  return hooks;
}

/// The file next to `path` with extension `ext`, matched case-insensitively; the lower-case
/// name when there is none (so that messages name what was expected).
fs::path companion(const fs::path& path, const std::string& ext, bool* found) {
  fs::path wanted = path;
  wanted.replace_extension(ext);
  *found = false;
  std::error_code error;
  const fs::path dir = wanted.has_parent_path() ? wanted.parent_path() : fs::path(".");
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    if (iequals(entry.path().filename().string(), wanted.filename().string())) {
      *found = true;
      return entry.path();
    }
  }
  return wanted;
}

bool family_accepts(ShapeFamily family, int type) {
  if (family == ShapeFamily::kPoint) {
    return type == SHPT_POINT || type == SHPT_POINTZ || type == SHPT_POINTM;
  }
  if (family == ShapeFamily::kPolygon) {
    return type == SHPT_POLYGON || type == SHPT_POLYGONZ || type == SHPT_POLYGONM;
  }
  return type == SHPT_ARC || type == SHPT_ARCZ || type == SHPT_ARCM;
}

const char* family_name(ShapeFamily family) {
  return family == ShapeFamily::kPoint     ? "Point/PointZ (1/11)"
         : family == ShapeFamily::kPolygon ? "Polygon/PolygonZ (5/15)"
                                           : "PolyLine/PolyLineZ (3/13)";
}

uint32_t big_endian(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

}  // namespace

// --- ShapeReader -------------------------------------------------------------------------------

ShapeReader::ShapeReader(const fs::path& shp, ShapeFamily family) : file_(shp.string()) {
  bool found = false;
  const fs::path shx = companion(shp, ".shx", &found);
  if (!found) {
    fail(shx.string(), -1, "missing Shapefile index (.shx); it must sit next to " + file_);
  }
  check_input_file(shp);
  check_input_file(shx);
  SAHooks hooks = make_hooks();
  SHPHandle handle = SHPOpenLL(shp.c_str(), "rb", &hooks);
  if (handle == nullptr) {
    fail(file_, -1, "cannot open as a Shapefile (unreadable, or the .shp/.shx header is corrupt)");
  }
  handle_ = handle;
  int type = 0;
  SHPGetInfo(handle, &count_, &type, nullptr, nullptr);
  if (!family_accepts(family, type)) {
    SHPClose(handle);
    handle_ = nullptr;
    fail(file_, -1,
         "wrong shape type " + std::to_string(type) + " (expected " + family_name(family) + ")");
  }
  type_ = type;
  has_z_ = type == SHPT_POINTZ || type == SHPT_ARCZ || type == SHPT_POLYGONZ;
  try {
    check_index(shx);
  } catch (...) {
    SHPClose(handle);
    handle_ = nullptr;
    throw;
  }
}

void ShapeReader::check_index(const fs::path& shx) const {
  // ESRI Shapefile Technical Description (1998): the .shp holds, from byte 100, records of an
  // 8-byte header (record number from 1, content length in 16-bit words, both big-endian) and
  // their content; the .shx holds, from byte 100, one 8-byte entry per record (offset in words,
  // content length in words).
  std::FILE* shp_file = std::fopen(file_.c_str(), "rb");
  std::FILE* shx_file = std::fopen(shx.c_str(), "rb");
  const auto close = [&] {
    if (shp_file != nullptr) std::fclose(shp_file);
    if (shx_file != nullptr) std::fclose(shx_file);
  };
  if (shp_file == nullptr || shx_file == nullptr) {
    close();
    fail(shp_file == nullptr ? file_ : shx.string(), -1, "cannot be read");
  }
  unsigned char entry[8];
  unsigned char header[8];
  long position = 100;
  std::string problem;
  bool shp_short = false;
  int record = 0;
  for (; record < count_; ++record) {
    if (std::fseek(shx_file, 100 + 8L * record, SEEK_SET) != 0 ||
        std::fread(entry, 1, 8, shx_file) != 8) {
      problem = "the index ends before its record count";
      break;
    }
    const long offset = 2L * big_endian(entry);
    const uint32_t length = big_endian(entry + 4);
    if (std::fseek(shp_file, position, SEEK_SET) != 0 || std::fread(header, 1, 8, shp_file) != 8) {
      problem = "truncated or corrupt: the file ends before this record";
      shp_short = true;
      break;
    }
    const uint32_t number = big_endian(header);
    const uint32_t shp_length = big_endian(header + 4);
    if (offset != position || length != shp_length || number != uint32_t(record) + 1) {
      problem = "the index says offset " + std::to_string(offset) + " and length " +
                std::to_string(2L * length) + " bytes, but " + fs::path(file_).filename().string() +
                " has record " + std::to_string(number) + " of " + std::to_string(2L * shp_length) +
                " bytes at offset " + std::to_string(position) +
                " (an index of another file, or a damaged one, would pair shapes with the wrong "
                "attributes)";
      break;
    }
    position += 8 + 2L * static_cast<long>(shp_length);
  }
  close();
  if (!problem.empty()) {
    fail(shp_short ? file_ : shx.string(), record, problem);
  }
}

ShapeReader::~ShapeReader() {
  if (handle_ != nullptr) {
    SHPClose(static_cast<SHPHandle>(handle_));
  }
}

bool ShapeReader::read(int index, std::vector<Point3>& points, int& parts) const {
  auto handle = static_cast<SHPHandle>(handle_);
  std::unique_ptr<SHPObject, void (*)(SHPObject*)> object(SHPReadObject(handle, index),
                                                          SHPDestroyObject);
  if (!object) {
    fail(file_, index, "truncated or corrupt shape record");
  }
  // ESRI Shapefile Technical Description (1998), "Main File Record Contents": all non-Null shapes
  // of a file have the file's type. Anything else is a record read from garbage (a .shp
  // overwritten or not matching its .shx), which must not pass as a record without geometry.
  if (object->nSHPType != SHPT_NULL && object->nSHPType != type_) {
    fail(file_, index,
         "corrupt shape record: shape type " + std::to_string(object->nSHPType) +
             " in a layer of type " + std::to_string(type_) +
             " (the .shp is damaged or does not match its .shx)");
  }
  if (object->nSHPType == SHPT_NULL || object->nVertices <= 0) {
    points.clear();
    parts = 0;
    return false;
  }
  points.resize(static_cast<size_t>(object->nVertices));
  for (int i = 0; i < object->nVertices; ++i) {
    const double z = (has_z_ && object->padfZ != nullptr) ? object->padfZ[i] : 0.0;
    if (!std::isfinite(object->padfX[i]) || !std::isfinite(object->padfY[i]) || !std::isfinite(z)) {
      fail(file_, index,
           "corrupt shape record: vertex " + std::to_string(i) +
               " has a coordinate that is not a finite number");
    }
    // ESRI Shapefile Technical Description: a multi-vertex record starts with the box of its
    // points (and its Z range). A vertex outside it is a damaged coordinate (one flipped byte
    // turned 4124484 into 6e290, and the road fit then ran for ever), never real data.
    const auto outside = [](double value, double low, double high) {
      const double slack = 1e-3 + 1e-9 * std::max(std::abs(low), std::abs(high));
      return value < low - slack || value > high + slack;
    };
    if (object->nSHPType != SHPT_POINT && object->nSHPType != SHPT_POINTZ &&
        (outside(object->padfX[i], object->dfXMin, object->dfXMax) ||
         outside(object->padfY[i], object->dfYMin, object->dfYMax) ||
         (has_z_ && object->padfZ != nullptr && outside(z, object->dfZMin, object->dfZMax)))) {
      fail(file_, index,
           "corrupt shape record: vertex " + std::to_string(i) + " (" +
               format_significant(object->padfX[i], 10) + ", " +
               format_significant(object->padfY[i], 10) + ", " + format_significant(z, 10) +
               ") lies outside the record's bounding box");
    }
    points[static_cast<size_t>(i)] = Point3{object->padfX[i], object->padfY[i], z};
  }
  parts = object->nParts;
  return true;
}

// --- DbfReader ---------------------------------------------------------------------------------

DbfReader::DbfReader(const fs::path& dbf) : file_(dbf.string()) {
  bool found = false;
  const fs::path existing = companion(dbf, dbf.extension().string(), &found);
  if (found) {
    check_input_file(existing);
  }
  SAHooks hooks = make_hooks();
  DBFHandle handle = DBFOpenLL(dbf.c_str(), "rb", &hooks);
  if (handle == nullptr) {
    fail(file_, -1, "cannot open as a dBASE table (missing, unreadable or corrupt header)");
  }
  handle_ = handle;
  count_ = DBFGetRecordCount(handle);
  const int fields = DBFGetFieldCount(handle);
  for (int i = 0; i < fields; ++i) {
    names_.push_back(field_name(i));
  }
}

DbfReader::~DbfReader() {
  if (handle_ != nullptr) {
    DBFClose(static_cast<DBFHandle>(handle_));
  }
}

std::string DbfReader::field_name(int field) const {
  char name[XBASE_FLDNAME_LEN_READ + 1] = {};
  int width = 0;
  int decimals = 0;
  DBFGetFieldInfo(static_cast<DBFHandle>(handle_), field, name, &width, &decimals);
  return std::string(trim(name));
}

int DbfReader::find(std::string_view name) const {
  for (size_t i = 0; i < names_.size(); ++i) {
    if (iequals(names_[i], name)) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int DbfReader::require(std::string_view name) const {
  const int index = find(name);
  if (index < 0) {
    std::string found;
    for (const auto& field : names_) {
      found += (found.empty() ? "" : ", ") + field;
    }
    fail(file_, -1,
         "required field '" + std::string(name) + "' is missing (fields: " + found + ")");
  }
  return index;
}

std::string DbfReader::text(int record, int field) const {
  if (field < 0) {
    return {};
  }
  auto handle = static_cast<DBFHandle>(handle_);
  const char* value = DBFReadStringAttribute(handle, record, field);
  if (value != nullptr && DBFIsAttributeNULL(handle, record, field)) {
    return {};
  }
  if (value == nullptr) {
    fail(file_, record, "cannot read the record (truncated .dbf?)");
  }
  return std::string(trim(value));
}

std::optional<int64_t> DbfReader::integer(int record, int field) const {
  const std::string value = text(record, field);
  if (value.empty()) {
    return std::nullopt;
  }
  if (auto number = parse_int(value)) {
    return number;
  }
  // Numeric DBF fields may carry a decimal part ("40.000") for an integer quantity.
  if (auto number = parse_double(value);
      number && *number == static_cast<double>(static_cast<int64_t>(*number))) {
    return static_cast<int64_t>(*number);
  }
  fail(file_, record,
       "field '" + names_[static_cast<size_t>(field)] + "' is not an integer: '" + value + "'");
}

std::optional<double> DbfReader::real(int record, int field) const {
  const std::string value = text(record, field);
  if (value.empty()) {
    return std::nullopt;
  }
  if (auto number = parse_double(value)) {
    return number;
  }
  fail(file_, record,
       "field '" + names_[static_cast<size_t>(field)] + "' is not a number: '" + value + "'");
}

}  // namespace corsa::ngii::detail
