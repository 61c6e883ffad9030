// Entity shapes from the users' model3d files (see ModelShapeSource in model_io.h).

#include <algorithm>
#include <cmath>

#include "corsa/sensors/model_io.h"
#include "material_defaults.h"

namespace corsa::sensors {
namespace {

const char* category_name(engine::EntityCategory c) {
  using engine::EntityCategory;
  switch (c) {
    case EntityCategory::kCar:
      return "car";
    case EntityCategory::kVan:
      return "van";
    case EntityCategory::kTruck:
      return "truck";
    case EntityCategory::kTrailer:
      return "trailer";
    case EntityCategory::kSemitrailer:
      return "semitrailer";
    case EntityCategory::kBus:
      return "bus";
    case EntityCategory::kMotorbike:
      return "motorbike";
    case EntityCategory::kBicycle:
      return "bicycle";
    case EntityCategory::kTrain:
      return "train";
    case EntityCategory::kTram:
      return "tram";
    case EntityCategory::kPedestrian:
      return "pedestrian";
    case EntityCategory::kWheelchair:
      return "wheelchair";
    case EntityCategory::kAnimal:
      return "animal";
    case EntityCategory::kObstacle:
      return "obstacle";
  }
  return "obstacle";
}

/// The meshes of a model as one mesh: palettes merged, uvs padded where a part has none.
StaticMesh merge(const std::vector<StaticMesh>& parts, SemanticClass semantic) {
  StaticMesh out;
  out.classes = {semantic};
  bool any_uv = false;
  for (const StaticMesh& p : parts) {
    any_uv = any_uv || !p.uvs.empty();
  }
  for (const StaticMesh& p : parts) {
    const auto base = static_cast<uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), p.vertices.begin(), p.vertices.end());
    if (any_uv) {
      if (p.uvs.size() == p.vertices.size()) {
        out.uvs.insert(out.uvs.end(), p.uvs.begin(), p.uvs.end());
      } else {
        out.uvs.resize(out.vertices.size(), {0.0f, 0.0f});
      }
    }
    const auto palette = static_cast<uint16_t>(out.materials.size());
    if (p.materials.empty()) {
      out.materials.push_back(
          p.color ? materials::plain(p.name, linear_rgb(p.color->r, p.color->g, p.color->b), 0.5)
                  : detail::default_material(semantic));
    } else {
      out.materials.insert(out.materials.end(), p.materials.begin(), p.materials.end());
    }
    for (size_t t = 0; t < p.triangles.size(); ++t) {
      const auto& tri = p.triangles[t];
      out.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
      const uint16_t local = p.material_indices.size() == p.triangles.size() ? p.material_indices[t]
                             : p.material_indices.size() == 1                ? p.material_indices[0]
                                                                             : 0;
      out.material_indices.push_back(static_cast<uint16_t>(palette + local));
    }
  }
  return out;
}

}  // namespace

const std::vector<std::string>& entity_category_names() {
  static const std::vector<std::string> names = [] {
    using engine::EntityCategory;
    std::vector<std::string> out;
    for (const EntityCategory c :
         {EntityCategory::kCar, EntityCategory::kVan, EntityCategory::kTruck,
          EntityCategory::kTrailer, EntityCategory::kSemitrailer, EntityCategory::kBus,
          EntityCategory::kMotorbike, EntityCategory::kBicycle, EntityCategory::kTrain,
          EntityCategory::kTram, EntityCategory::kPedestrian, EntityCategory::kWheelchair,
          EntityCategory::kAnimal, EntityCategory::kObstacle}) {
      out.emplace_back(category_name(c));
    }
    return out;
  }();
  return names;
}

ModelShapeSource::ModelShapeSource(std::filesystem::path base, Diagnostics& diagnostics,
                                   std::vector<EntityModel> models, std::string rig_file)
    : base_(std::move(base)),
      diagnostics_(diagnostics),
      models_(std::move(models)),
      rig_file_(std::move(rig_file)) {}

const EntityModel* ModelShapeSource::model_for(const engine::EntitySnapshot& e) const {
  const EntityModel* by_category = nullptr;
  for (const EntityModel& m : models_) {
    if (!m.entity.empty() && m.entity == e.name) {
      return &m;
    }
    if (by_category == nullptr && m.entity.empty() && m.category == category_name(e.category)) {
      by_category = &m;
    }
  }
  return by_category;
}

bool ModelShapeSource::names_model(const engine::EntitySnapshot& e) const {
  return !e.model3d.empty() || model_for(e) != nullptr;
}

bool ModelShapeSource::shape_of(const engine::EntitySnapshot& e, StaticMesh& mesh) {
  std::filesystem::path file = e.model3d;
  const EntityModel* chosen = nullptr;
  if (file.empty()) {
    chosen = model_for(e);
    if (chosen == nullptr) {
      return false;
    }
    file = chosen->file;  // already resolved against the rig's folder
  } else if (file.is_relative()) {
    file = base_ / file;
  }
  const SemanticClass semantic = semantic_class_of_entity(e.category);
  auto& slot = loaded_[file.string()];
  if (!slot) {
    try {
      ModelPlacement placement;
      placement.semantic = semantic;
      placement.diagnostics = &diagnostics_;
      slot = load_model(file, placement);
    } catch (const InputError& error) {
      // A rig's model is reported at its element; a model3d at the file it names.
      diagnostics_.add_once(
          "model3d:" + file.string(),
          chosen != nullptr
              ? make_warning(chosen->origin.empty() ? rig_file_ : chosen->origin, chosen->line,
                             "cannot use the model '" + file.string() + "' for entity '" + e.name +
                                 "' (" + error.diagnostic().message +
                                 "); generated shapes stand in")
              : make_warning(file.string(), 0,
                             "cannot use the model of entity '" + e.name + "' (" +
                                 error.diagnostic().message + "); a generated shape stands in"));
      slot = std::vector<StaticMesh>{};
    }
  }
  if (slot->empty()) {
    return false;
  }
  mesh = merge(*slot, semantic);
  // Stretch the model's bounds onto the entity's bounding box.
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Vec3& v : mesh.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  const Vec3 size = hi - lo;
  const Vec3 centre = (lo + hi) * 0.5;
  auto scale = [](double want, double have) { return have > 1e-9 ? want / have : 1.0; };
  const Vec3 k{scale(e.box.length, size.x), scale(e.box.width, size.y),
               scale(e.box.height, size.z)};
  for (Vec3& v : mesh.vertices) {
    v = {e.box.center_x + (v.x - centre.x) * k.x, e.box.center_y + (v.y - centre.y) * k.y,
         e.box.center_z + (v.z - centre.z) * k.z};
  }
  mesh.name = file.string();
  return true;
}

}  // namespace corsa::sensors
