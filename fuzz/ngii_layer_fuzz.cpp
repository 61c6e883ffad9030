// libFuzzer target: one NGII layer as the converter reads it, from bytes: the .shp, .shx, .dbf
// and .prj cut apart at the part separator (fuzz_parts.h), written into a scratch folder (shapelib
// and PROJ read files). The first byte's low two bits choose the geometry the layer must have
// (point, line, polygon). Every record's geometry is read, every NGII field of every record as text
// (decoded from CP949), integer or real as read_layers reads it, and, when the first byte's bit 2
// is set, the .prj through PROJ (PROJ's identification against its database takes about half a
// second of CPU, which would otherwise leave the shapes and attributes a few runs per second). Bad
// input must end in corsa::InputError, never a crash, a hang or a sanitizer report.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "cp949.h"
#include "crs.h"
#include "fuzz_parts.h"
#include "shapefile.h"

namespace {

namespace fs = std::filesystem;
using corsa::ngii::detail::ShapeFamily;

// The DBF fields read_layers looks up (../shared/data/ngii/README.md), and how it reads them.
const std::vector<std::string> kTextFields{
    "ID",         "NodeType", "LinkType", "RoadRank", "RoadType", "RoadNo",  "R_LinkID", "L_LinkID",
    "FromNodeID", "ToNodeID", "Type",     "Kind",     "LinkID",   "SubType", "Remark",   "Name"};
const std::vector<std::string> kIntegerFields{"LaneNo", "MaxSpeed", "Ref_Lane"};
const std::vector<std::string> kRealFields{"Length"};

void read_geometry(const fs::path& shp, ShapeFamily family) {
  const corsa::ngii::detail::ShapeReader shapes(shp, family);
  std::vector<corsa::Vec3> points;
  for (int i = 0; i < shapes.count(); ++i) {
    int parts = 0;
    (void)shapes.read(i, points, parts);
  }
}

void read_attributes(const fs::path& dbf) {
  const corsa::ngii::detail::DbfReader table(dbf);
  corsa::ngii::detail::Cp949Decoder decoder;
  for (int record = 0; record < table.count(); ++record) {
    for (const auto& name : kTextFields) {
      bool invalid = false;
      (void)decoder.decode(table.text(record, table.find(name)), &invalid);
    }
    for (const auto& name : kIntegerFields) (void)table.integer(record, table.find(name));
    for (const auto& name : kRealFields) (void)table.real(record, table.find(name));
  }
  (void)table.require("ID");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const fs::path kScratch = corsa::fuzz::scratch_folder("ngii_layer_fuzz");
  if (size == 0) return 0;
  const ShapeFamily family = static_cast<ShapeFamily>((data[0] & 3) % 3);
  const auto parts = corsa::fuzz::split_parts(data + 1, size - 1, 4);
  const fs::path base = kScratch / "C1_TRAFFICLIGHT";
  const char* extensions[] = {".shp", ".shx", ".dbf", ".prj"};
  for (size_t i = 0; i < 4; ++i) {
    corsa::fuzz::write_bytes(fs::path(base).concat(extensions[i]), parts[i]);
  }
  try {
    read_geometry(fs::path(base).concat(".shp"), family);
  } catch (const corsa::InputError&) {
  }
  try {
    read_attributes(fs::path(base).concat(".dbf"));
  } catch (const corsa::InputError&) {
  }
  try {
    if ((data[0] & 4) != 0) (void)corsa::ngii::detail::read_crs(fs::path(base).concat(".prj"));
  } catch (const corsa::InputError&) {
  }
  return 0;
}
