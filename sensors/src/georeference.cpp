#include "corsa/sensors/georeference.h"

#include <proj.h>

#include <cmath>

#include "corsa/core/diagnostic.h"

namespace corsa::sensors {

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

CrsTransform::CrsTransform(const std::string& from, const std::string& to)
    : impl_(std::make_unique<Impl>()) {
  // A context per transform: PROJ objects are not shared between threads or instances.
  impl_->context = proj_context_create();
  proj_log_level(impl_->context, PJ_LOG_NONE);  // failures are reported by the exception
  PJ* raw = proj_create_crs_to_crs(impl_->context, from.c_str(), to.c_str(), nullptr);
  if (raw == nullptr) {
    const int error = proj_context_errno(impl_->context);
    throw InputError(make_error("", 0,
                                "cannot transform coordinates from '" + from + "' to '" + to +
                                    "': " + proj_context_errno_string(impl_->context, error)));
  }
  impl_->transform = proj_normalize_for_visualization(impl_->context, raw);
  proj_destroy(raw);
  if (impl_->transform == nullptr) {
    throw InputError(make_error("", 0, "cannot normalise the axis order of '" + from + "'"));
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

Vec3 CrsTransform::apply(Vec3 p) const {
  const PJ_COORD out = proj_trans(impl_->transform, PJ_FWD, proj_coord(p.x, p.y, p.z, 0.0));
  if (!std::isfinite(out.xyz.x) || !std::isfinite(out.xyz.y)) {
    throw InputError(make_error("", 0, "coordinate outside the valid area of the CRS"));
  }
  return {out.xyz.x, out.xyz.y, out.xyz.z};
}

GeoLocation geolocation_of(const std::string& map_crs, Vec3 map_point) {
  const CrsTransform to_wgs84(map_crs, "EPSG:4326");
  const Vec3 g = to_wgs84.apply(map_point);
  return {g.y, g.x};
}

}  // namespace corsa::sensors
