#include "crs.h"

#include <proj.h>

#include <memory>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"

namespace corsa::ngii::detail {
namespace {

struct ContextDeleter {
  void operator()(PJ_CONTEXT* context) const { proj_context_destroy(context); }
};
struct ObjectDeleter {
  void operator()(PJ* object) const { proj_destroy(object); }
};
struct ListDeleter {
  void operator()(PJ_OBJ_LIST* list) const { proj_list_destroy(list); }
};
using Context = std::unique_ptr<PJ_CONTEXT, ContextDeleter>;
using Object = std::unique_ptr<PJ, ObjectDeleter>;
using List = std::unique_ptr<PJ_OBJ_LIST, ListDeleter>;

[[noreturn]] void fail(const std::filesystem::path& prj, const std::string& message) {
  throw InputError(make_error(prj.string(), 0, message));
}

/// "EPSG:32652" when PROJ's database recognises the CRS with high confidence, else "".
std::string identify(PJ_CONTEXT* context, const PJ* crs) {
  int* confidence = nullptr;
  List matches(proj_identify(context, crs, "EPSG", nullptr, &confidence));
  std::string result;
  if (matches && proj_list_get_count(matches.get()) > 0 && confidence != nullptr &&
      confidence[0] >= 70) {
    Object best(proj_list_get(context, matches.get(), 0));
    const char* authority = proj_get_id_auth_name(best.get(), 0);
    const char* code = proj_get_id_code(best.get(), 0);
    if (authority != nullptr && code != nullptr) {
      result = std::string(authority) + ":" + code;
    }
  }
  proj_int_list_destroy(confidence);
  return result;
}

}  // namespace

Crs read_crs(const std::filesystem::path& prj) {
  Crs crs;
  crs.wkt = std::string(trim(read_file(prj)));
  if (crs.wkt.empty()) {
    fail(prj, "empty .prj: the layers' coordinate reference system is unknown");
  }
  Context context(proj_context_create());
  proj_log_level(context.get(), PJ_LOG_NONE);
  proj_context_set_enable_network(context.get(), 0);
  Object object(proj_create(context.get(), crs.wkt.c_str()));
  if (!object) {
    fail(prj, "PROJ cannot read this coordinate reference system: " +
                  std::string(
                      proj_context_errno_string(context.get(), proj_context_errno(context.get()))));
  }
  if (proj_get_type(object.get()) != PJ_TYPE_PROJECTED_CRS) {
    fail(prj, "not a projected CRS: the converter needs planar coordinates in metres");
  }
  const char* name = proj_get_name(object.get());
  crs.name = name != nullptr ? name : "";
  const char* proj_string = proj_as_proj_string(context.get(), object.get(), PJ_PROJ_5, nullptr);
  if (proj_string == nullptr) {
    fail(prj, "PROJ cannot express this CRS as a PROJ string");
  }
  crs.proj_string = proj_string;
  // "+type=crs" is PROJ's marker for CRS objects; OpenDRIVE readers expect the plain string.
  if (const auto at = crs.proj_string.find(" +type=crs"); at != std::string::npos) {
    crs.proj_string.erase(at, 10);
  }
  if (crs.proj_string.find("+units=m") == std::string::npos) {
    fail(prj, "the projected CRS is not in metres (" + crs.proj_string + ")");
  }
  crs.authority = identify(context.get(), object.get());
  return crs;
}

}  // namespace corsa::ngii::detail
