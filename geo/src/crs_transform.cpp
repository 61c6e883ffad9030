#include "corsa/geo/crs_transform.h"

#include <proj.h>

#include <cmath>

#include "corsa/core/diagnostic.h"

namespace corsa::geo {
namespace {

// OpenDRIVE geoReferences are PROJ strings written without PROJ's "+type=crs" marker (ngii's
// writer strips it, as other readers expect); without it proj_create reads the string as a
// coordinate operation, not as the CRS it describes.
std::string as_crs(const std::string& definition) {
  const size_t start = definition.find_first_not_of(" \t\r\n");
  if (start == std::string::npos || definition[start] != '+' ||
      definition.find("+type=crs") != std::string::npos) {
    return definition;
  }
  return definition + " +type=crs";
}

}  // namespace

struct CrsTransform::Impl {
  PJ_CONTEXT* context = nullptr;
  PJ* transform = nullptr;
  ~Impl() {
    if (transform != nullptr) {
      proj_destroy(transform);
    }
    if (context != nullptr) {
      proj_context_destroy(context);
    }
  }
};

CrsTransform::CrsTransform(const std::string& from_text, const std::string& to_text)
    : impl_(std::make_unique<Impl>()) {
  const std::string from = as_crs(from_text);
  const std::string to = as_crs(to_text);
  // A context per transform: PROJ objects are not shared between threads or instances.
  impl_->context = proj_context_create();
  proj_log_level(impl_->context, PJ_LOG_NONE);  // failures are reported by the exception
  PJ* raw = proj_create_crs_to_crs(impl_->context, from.c_str(), to.c_str(), nullptr);
  if (raw == nullptr) {
    const int error = proj_context_errno(impl_->context);
    throw InputError(make_error("", 0,
                                "cannot transform coordinates from '" + from_text + "' to '" +
                                    to_text +
                                    "': " + proj_context_errno_string(impl_->context, error)));
  }
  impl_->transform = proj_normalize_for_visualization(impl_->context, raw);
  proj_destroy(raw);
  if (impl_->transform == nullptr) {
    throw InputError(make_error("", 0, "cannot normalise the axis order of '" + from_text + "'"));
  }
  PJ* source = proj_create(impl_->context, from.c_str());
  if (source != nullptr) {
    const PJ_TYPE type = proj_get_type(source);
    source_geographic_ = type == PJ_TYPE_GEOGRAPHIC_2D_CRS || type == PJ_TYPE_GEOGRAPHIC_3D_CRS;
    proj_destroy(source);
  }
}

CrsTransform::~CrsTransform() = default;
CrsTransform::CrsTransform(CrsTransform&&) noexcept = default;
CrsTransform& CrsTransform::operator=(CrsTransform&&) noexcept = default;

std::optional<Vec3> CrsTransform::try_apply(Vec3 p) const {
  const PJ_COORD out = proj_trans(impl_->transform, PJ_FWD, proj_coord(p.x, p.y, p.z, 0.0));
  if (!std::isfinite(out.xyz.x) || !std::isfinite(out.xyz.y)) {
    return std::nullopt;
  }
  return Vec3{out.xyz.x, out.xyz.y, out.xyz.z};
}

Vec3 CrsTransform::apply(Vec3 p) const {
  const auto out = try_apply(p);
  if (!out) {
    throw InputError(make_error("", 0, "coordinate outside the valid area of the CRS"));
  }
  return *out;
}

GeographicToProjected geographic_to_projected(const std::string& crs) {
  auto transform = std::make_shared<const CrsTransform>("EPSG:4326", crs);
  return [transform](double latitude_deg, double longitude_deg) -> std::optional<Vec2> {
    const auto p = transform->try_apply({longitude_deg, latitude_deg, 0.0});
    return p ? std::optional<Vec2>(Vec2{p->x, p->y}) : std::nullopt;
  };
}

}  // namespace corsa::geo
