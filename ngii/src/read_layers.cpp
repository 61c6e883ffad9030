// Layer import (A1/A2/B2/C1 and the feature layers B1, B3, C3, C4, C6, A3, A4, A5): shapelib for
// geometry and attributes, CP949 text, CRS from the .prj.

#include <algorithm>
#include <unordered_map>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/ngii/layers.h"
#include "cp949.h"
#include "crs.h"
#include "shapefile.h"

namespace corsa::ngii {
namespace {

namespace fs = std::filesystem;
using detail::Cp949Decoder;
using detail::DbfReader;
using detail::ShapeFamily;
using detail::ShapeReader;

[[noreturn]] void fail(const std::string& file, int64_t record, std::string message) {
  Diagnostic diagnostic = make_error(file, 0, std::move(message));
  diagnostic.record = record;
  throw InputError(std::move(diagnostic));
}

/// `dir/<name>` matched case-insensitively; empty when absent.
fs::path find_file(const fs::path& dir, const std::string& name) {
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    if (iequals(entry.path().filename().string(), name)) {
      return entry.path();
    }
  }
  return {};
}

/// The three files of one layer. `required` layers must have all three; optional layers are
/// skipped when the .shp is absent but must then be complete.
struct LayerFiles {
  fs::path shp;
  fs::path dbf;
  fs::path prj;
  bool present = false;
};

LayerFiles locate_layer(const fs::path& dir, const std::string& base, bool required) {
  LayerFiles files;
  files.shp = find_file(dir, base + ".shp");
  files.dbf = find_file(dir, base + ".dbf");
  files.prj = find_file(dir, base + ".prj");
  const bool any =
      !files.shp.empty() || !files.dbf.empty() || !find_file(dir, base + ".shx").empty();
  if (!required && !any) {
    return files;
  }
  if (files.shp.empty()) {
    fail((dir / (base + ".shp")).string(), -1, "missing layer geometry (.shp)");
  }
  if (files.dbf.empty()) {
    fail((dir / (base + ".dbf")).string(), -1, "missing layer attributes (.dbf)");
  }
  files.present = true;
  return files;
}

/// Opens a layer's geometry and attributes and checks that they describe the same records.
struct OpenLayer {
  ShapeReader shapes;
  DbfReader table;
  OpenLayer(const LayerFiles& files, ShapeFamily family)
      : shapes(files.shp, family), table(files.dbf) {
    if (shapes.count() != table.count()) {
      fail(table.file(), -1,
           std::to_string(table.count()) + " records but " + files.shp.filename().string() +
               " has " + std::to_string(shapes.count()) + " shapes");
    }
  }
};

/// Reads text fields, decoding CP949 and warning once per layer about undecodable bytes.
class TextReader {
 public:
  TextReader(const DbfReader& table, Cp949Decoder& decoder, Diagnostics& diagnostics)
      : table_(table), decoder_(decoder), diagnostics_(diagnostics) {}
  std::string operator()(int record, int field) {
    bool invalid = false;
    std::string text = decoder_.decode(table_.text(record, field), &invalid);
    if (invalid) {
      Diagnostic warning = make_warning(table_.file(), 0,
                                        "text that is not valid CP949 (shown "
                                        "as U+FFFD); first seen here");
      warning.record = record;
      diagnostics_.add_once("ngii-cp949:" + table_.file(), std::move(warning));
    }
    return text;
  }

 private:
  const DbfReader& table_;
  Cp949Decoder& decoder_;
  Diagnostics& diagnostics_;
};

void warn_missing_z(const ShapeReader& shapes, Diagnostics& diagnostics) {
  if (!shapes.has_z()) {
    diagnostics.add_once("ngii-no-z:" + shapes.file(),
                         make_warning(shapes.file(), 0, "layer has no Z; heights taken as 0"));
  }
}

[[noreturn]] void null_shape(const ShapeReader& shapes, int record) {
  fail(shapes.file(), record, "record has no geometry");
}

/// Counts records without geometry in an optional layer; they are skipped with one located note
/// (a Null shape is a valid Shapefile record, ESRI Shapefile Technical Description, "Null Shapes":
/// there is nothing to draw, and nothing is guessed).
class SkippedShapes {
 public:
  SkippedShapes(const ShapeReader& shapes, Diagnostics& diagnostics)
      : shapes_(shapes), diagnostics_(diagnostics) {}
  void add(int record) {
    if (count_++ == 0) {
      first_ = record;
    }
  }
  ~SkippedShapes() {
    if (count_ > 0) {
      Diagnostic note = make_warning(
          shapes_.file(), 0,
          std::to_string(count_) + " record(s) without geometry skipped (the first is this one)");
      note.severity = Severity::kNote;
      note.record = first_;
      diagnostics_.add(std::move(note));
    }
  }

 private:
  const ShapeReader& shapes_;
  Diagnostics& diagnostics_;
  int count_ = 0;
  int first_ = 0;
};

std::vector<Node> read_nodes(const LayerFiles& files, Cp949Decoder& decoder,
                             Diagnostics& diagnostics) {
  OpenLayer layer(files, ShapeFamily::kPoint);
  warn_missing_z(layer.shapes, diagnostics);
  TextReader text(layer.table, decoder, diagnostics);
  const int id = layer.table.require("ID");
  const int type = layer.table.find("NodeType");
  std::vector<Node> nodes(static_cast<size_t>(layer.table.count()));
  std::vector<Point3> scratch;
  for (int i = 0; i < layer.table.count(); ++i) {
    Node& node = nodes[static_cast<size_t>(i)];
    node.id = text(i, id);
    node.node_type = text(i, type);
    int parts = 0;
    if (!layer.shapes.read(i, scratch, parts)) {
      null_shape(layer.shapes, i);
    }
    node.position = scratch.front();
    node.record = i;
  }
  return nodes;
}

/// A2 field indices; the names tolerate the case quirks of real data (`L_LinKID`).
struct LinkFields {
  int id, link_type, lane_no, right, left, from, to;
  int road_rank, road_type, road_no, max_speed, length;
  explicit LinkFields(const DbfReader& table)
      : id(table.require("ID")),
        link_type(table.require("LinkType")),
        lane_no(table.require("LaneNo")),
        right(table.require("R_LinkID")),
        left(table.require("L_LinkID")),
        from(table.require("FromNodeID")),
        to(table.require("ToNodeID")),
        road_rank(table.find("RoadRank")),
        road_type(table.find("RoadType")),
        road_no(table.find("RoadNo")),
        max_speed(table.find("MaxSpeed")),
        length(table.find("Length")) {}
};

std::vector<Link> read_links(const LayerFiles& files, Cp949Decoder& decoder,
                             Diagnostics& diagnostics) {
  OpenLayer layer(files, ShapeFamily::kPolyline);
  warn_missing_z(layer.shapes, diagnostics);
  const DbfReader& table = layer.table;
  const LinkFields f(table);
  if (f.max_speed < 0) {
    diagnostics.add_once("ngii-no-maxspeed",
                         make_warning(table.file(), 0, "no MaxSpeed field: no speed limits"));
  }
  TextReader text(table, decoder, diagnostics);
  std::vector<Link> links(static_cast<size_t>(table.count()));
  for (int i = 0; i < table.count(); ++i) {
    Link& link = links[static_cast<size_t>(i)];
    link.record = i;
    link.id = text(i, f.id);
    link.link_type = text(i, f.link_type);
    link.road_rank = text(i, f.road_rank);
    link.road_type = text(i, f.road_type);
    link.road_no = text(i, f.road_no);
    link.right_id = text(i, f.right);
    link.left_id = text(i, f.left);
    link.from_node = text(i, f.from);
    link.to_node = text(i, f.to);
    link.lane_no = static_cast<int>(table.integer(i, f.lane_no).value_or(0));
    link.max_speed =
        f.max_speed < 0 ? 0 : static_cast<int>(table.integer(i, f.max_speed).value_or(0));
    link.length_attr = f.length < 0 ? 0.0 : table.real(i, f.length).value_or(0.0);
    if (link.id.empty()) {
      fail(table.file(), i, "link without an ID");
    }
    if (link.max_speed < 0) {
      fail(table.file(), i, "negative MaxSpeed " + std::to_string(link.max_speed));
    }
    int parts = 0;
    if (!layer.shapes.read(i, link.points, parts)) {
      null_shape(layer.shapes, i);
    }
    if (link.points.size() < 2) {
      fail(layer.shapes.file(), i, "link " + link.id + " has fewer than 2 vertices");
    }
    if (parts > 1) {
      Diagnostic warning =
          make_warning(layer.shapes.file(), 0, "multi-part link; its parts are joined in order");
      warning.record = i;
      diagnostics.add_once("ngii-multipart", std::move(warning));
    }
  }
  return links;
}

std::vector<SurfaceMark> read_marks(const LayerFiles& files, Cp949Decoder& decoder,
                                    Diagnostics& diagnostics) {
  OpenLayer layer(files, ShapeFamily::kPolyline);
  TextReader text(layer.table, decoder, diagnostics);
  const int id = layer.table.require("ID");
  const int type = layer.table.require("Type");
  const int kind = layer.table.require("Kind");
  const int right = layer.table.require("R_linkID");
  const int left = layer.table.require("L_linkID");
  std::vector<SurfaceMark> marks;
  marks.reserve(static_cast<size_t>(layer.table.count()));
  SkippedShapes skipped(layer.shapes, diagnostics);
  for (int i = 0; i < layer.table.count(); ++i) {
    SurfaceMark mark;
    int parts = 0;
    if (!layer.shapes.read(i, mark.points, parts)) {
      skipped.add(i);
      continue;
    }
    mark.record = i;
    mark.id = text(i, id);
    mark.type = text(i, type);
    mark.kind = text(i, kind);
    mark.right_link = text(i, right);
    mark.left_link = text(i, left);
    marks.push_back(std::move(mark));
  }
  return marks;
}

std::vector<TrafficLight> read_lights(const LayerFiles& files, Cp949Decoder& decoder,
                                      Diagnostics& diagnostics) {
  OpenLayer layer(files, ShapeFamily::kPoint);
  TextReader text(layer.table, decoder, diagnostics);
  const int id = layer.table.require("ID");
  const int type = layer.table.require("Type");
  const int link = layer.table.require("LinkID");
  const int ref_lane = layer.table.find("Ref_Lane");
  std::vector<TrafficLight> lights;
  lights.reserve(static_cast<size_t>(layer.table.count()));
  SkippedShapes skipped(layer.shapes, diagnostics);
  std::vector<Point3> scratch;
  for (int i = 0; i < layer.table.count(); ++i) {
    TrafficLight light;
    int parts = 0;
    if (!layer.shapes.read(i, scratch, parts)) {
      skipped.add(i);
      continue;
    }
    light.record = i;
    light.id = text(i, id);
    light.type = text(i, type);
    light.link_id = text(i, link);
    light.ref_lane =
        ref_lane < 0 ? 0 : static_cast<int>(layer.table.integer(i, ref_lane).value_or(0));
    light.position = scratch.front();
    lights.push_back(std::move(light));
  }
  return lights;
}

/// One feature layer's file base name, geometry and fields (manual 2023.07 §9.4.3-9.4.14).
struct FeatureSpec {
  const char* base;
  ShapeFamily family;
  const char* type;    ///< field read into Feature::type, or nullptr
  const char* kind;    ///< into Feature::kind
  const char* link;    ///< into Feature::link_id
  const char* remark;  ///< into Feature::remark
};

constexpr FeatureSpec kFeatureSpecs[8] = {
    {"B1_SAFETYSIGN", ShapeFamily::kPolygon, "Type", nullptr, "LinkID", "Remark"},
    {"B3_SURFACEMARK", ShapeFamily::kPolygon, "Type", "Kind", "LinkID", nullptr},
    {"C3_VEHICLEPROTECTIONSAFETY", ShapeFamily::kPolyline, "Type", "isCentral", nullptr, nullptr},
    {"C4_SPEEDBUMP", ShapeFamily::kPolygon, "Type", nullptr, "LinkID", nullptr},
    {"C6_POSTPOINT", ShapeFamily::kPoint, "Type", nullptr, nullptr, nullptr},
    {"A3_DRIVEWAYSECTION", ShapeFamily::kPolygon, "Kind", "RoadType", nullptr, nullptr},
    {"A4_SUBSIDIARYSECTION", ShapeFamily::kPolygon, "SubType", nullptr, nullptr, "Name"},
    {"A5_PARKINGLOT", ShapeFamily::kPolygon, "Type", nullptr, nullptr, nullptr},
};

void read_features(const LayerFiles& files, FeatureLayer layer, Cp949Decoder& decoder,
                   Diagnostics& diagnostics, std::vector<Feature>& out) {
  const FeatureSpec& spec = kFeatureSpecs[static_cast<size_t>(layer)];
  OpenLayer open(files, spec.family);
  TextReader text(open.table, decoder, diagnostics);
  const int id = open.table.require("ID");
  // The fields the spec marks NOT NULL are required; a Remark or Name may be missing.
  const int type = spec.type != nullptr ? open.table.require(spec.type) : -1;
  const int kind = spec.kind != nullptr ? open.table.require(spec.kind) : -1;
  const int link = spec.link != nullptr ? open.table.find(spec.link) : -1;
  const int remark = spec.remark != nullptr ? open.table.find(spec.remark) : -1;
  SkippedShapes skipped(open.shapes, diagnostics);
  for (int i = 0; i < open.table.count(); ++i) {
    Feature feature;
    int parts = 0;
    if (!open.shapes.read(i, feature.points, parts)) {
      skipped.add(i);
      continue;
    }
    feature.layer = layer;
    feature.record = i;
    feature.id = text(i, id);
    feature.type = text(i, type);
    feature.kind = text(i, kind);
    feature.link_id = text(i, link);
    feature.remark = text(i, remark);
    out.push_back(std::move(feature));
  }
}

template <typename Record>
void check_unique_ids(const std::vector<Record>& records, const std::string& file) {
  std::unordered_map<std::string_view, int64_t> seen;
  seen.reserve(records.size());
  for (const Record& record : records) {
    if (record.id.empty()) {
      continue;
    }
    const auto [it, inserted] = seen.emplace(record.id, record.record);
    if (!inserted) {
      fail(file, record.record,
           "duplicate ID " + record.id + " (also record " + std::to_string(it->second) + ")");
    }
  }
}

void check_link_nodes(const Layers& layers) {
  std::unordered_map<std::string_view, size_t> nodes;
  nodes.reserve(layers.nodes.size());
  for (size_t i = 0; i < layers.nodes.size(); ++i) {
    nodes.emplace(layers.nodes[i].id, i);
  }
  for (const Link& link : layers.links) {
    for (const std::string* node : {&link.from_node, &link.to_node}) {
      if (node->empty() || !nodes.contains(*node)) {
        const char* which = node == &link.from_node ? "FromNodeID" : "ToNodeID";
        fail(layers.link_file, link.record,
             "link " + link.id + ": " + which + " '" + *node + "' is not a node in " +
                 fs::path(layers.node_file).filename().string());
      }
    }
  }
}

/// The folder holding the layers: `path` itself, or the folder of a named A2_LINK.shp.
fs::path layer_dir(const fs::path& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    return path;
  }
  if (fs::is_regular_file(path, error)) {
    if (!iequals(path.filename().string(), "A2_LINK.shp")) {
      fail(path.string(), -1, "expected an NGII folder or its A2_LINK.shp");
    }
    return path.has_parent_path() ? path.parent_path() : fs::path(".");
  }
  fail(path.string(), -1, "no such file or folder");
}

}  // namespace

Layers read_layers(const fs::path& path, Diagnostics& diagnostics) {
  Layers layers;
  layers.dir = layer_dir(path);
  const LayerFiles node_files = locate_layer(layers.dir, "A1_NODE", true);
  const LayerFiles link_files = locate_layer(layers.dir, "A2_LINK", true);
  const LayerFiles mark_files = locate_layer(layers.dir, "B2_SURFACELINEMARK", false);
  const LayerFiles light_files = locate_layer(layers.dir, "C1_TRAFFICLIGHT", false);
  if (link_files.prj.empty()) {
    fail((layers.dir / "A2_LINK.prj").string(), -1,
         "missing projection (.prj): the coordinate reference system must not be guessed");
  }
  layers.crs = detail::read_crs(link_files.prj);
  for (const LayerFiles* other : {&node_files, &mark_files, &light_files}) {
    // Same text is the same CRS; only a differing .prj is worth a PROJ parse.
    if (other->present && !other->prj.empty() &&
        std::string(trim(read_file(other->prj))) != layers.crs.wkt &&
        detail::read_crs(other->prj).proj_string != layers.crs.proj_string) {
      fail(other->prj.string(), -1,
           "CRS differs from A2_LINK.prj (" + layers.crs.proj_string + ")");
    }
  }
  Cp949Decoder decoder;
  layers.node_file = node_files.dbf.string();
  layers.link_file = link_files.dbf.string();
  layers.nodes = read_nodes(node_files, decoder, diagnostics);
  layers.links = read_links(link_files, decoder, diagnostics);
  if (mark_files.present) {
    layers.mark_file = mark_files.dbf.string();
    layers.marks = read_marks(mark_files, decoder, diagnostics);
  }
  if (light_files.present) {
    layers.light_file = light_files.dbf.string();
    layers.lights = read_lights(light_files, decoder, diagnostics);
  }
  for (size_t k = 0; k < 8; ++k) {
    const LayerFiles files = locate_layer(layers.dir, kFeatureSpecs[k].base, false);
    if (!files.present) {
      continue;
    }
    if (!files.prj.empty() && std::string(trim(read_file(files.prj))) != layers.crs.wkt &&
        detail::read_crs(files.prj).proj_string != layers.crs.proj_string) {
      fail(files.prj.string(), -1, "CRS differs from A2_LINK.prj (" + layers.crs.proj_string + ")");
    }
    layers.feature_files[k] = files.dbf.string();
    read_features(files, static_cast<FeatureLayer>(k), decoder, diagnostics, layers.features);
  }
  check_unique_ids(layers.nodes, layers.node_file);
  check_unique_ids(layers.links, layers.link_file);
  check_link_nodes(layers);
  return layers;
}

}  // namespace corsa::ngii
