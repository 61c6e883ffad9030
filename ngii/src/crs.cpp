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

/// PROJ's own words for why it failed: the WKT parser's errors, else the messages it logged,
/// else its error code's text ("Unknown error (code 4096)" alone tells a user nothing).
std::string proj_reason(PJ_CONTEXT* context, const std::string& text, const std::string& logged) {
  std::string reason;
  PROJ_STRING_LIST warnings = nullptr;
  PROJ_STRING_LIST errors = nullptr;
  const char* const options[] = {"STRICT=NO", nullptr};
  Object wkt(proj_create_from_wkt(context, text.c_str(), options, &warnings, &errors));
  for (PROJ_STRING_LIST e = errors; e != nullptr && *e != nullptr; ++e) {
    reason += (reason.empty() ? "" : "; ") + std::string(*e);
  }
  proj_string_list_destroy(warnings);
  proj_string_list_destroy(errors);
  if (reason.empty()) {
    reason = logged;
  }
  if (reason.empty()) {
    reason = proj_context_errno_string(context, proj_context_errno(context));
  }
  // Only printable ASCII: PROJ may quote a piece of a binary file back.
  for (char& c : reason) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) {
      c = '?';
    }
  }
  return clip(reason, 200);
}

/// Collects what PROJ logs at error level (the context's own sink, no global state).
void collect_log(void* sink, int /*level*/, const char* message) {
  auto* text = static_cast<std::string*>(sink);
  std::string_view line = message != nullptr ? message : "";
  // "proj_create: missing ]": the function name is of no use to a user.
  if (const auto colon = line.find(": ");
      colon != std::string_view::npos && line.substr(0, colon).starts_with("proj_")) {
    line.remove_prefix(colon + 2);
  }
  if (!line.empty() && text->size() < 1000) {
    *text += (text->empty() ? "" : "; ") + std::string(line);
  }
}

}  // namespace

Crs read_crs(const std::filesystem::path& prj) {
  Crs crs;
  crs.wkt = std::string(trim(read_file(prj)));
  if (crs.wkt.empty()) {
    fail(prj, "empty .prj: the layers' coordinate reference system is unknown");
  }
  Context context(proj_context_create());
  std::string logged;
  proj_log_func(context.get(), &logged, collect_log);
  proj_log_level(context.get(), PJ_LOG_ERROR);
  proj_context_set_enable_network(context.get(), 0);
  Object object(proj_create(context.get(), crs.wkt.c_str()));
  if (!object) {
    proj_log_level(context.get(), PJ_LOG_NONE);
    fail(prj, "its coordinate reference system (WKT) could not be understood; PROJ says: " +
                  proj_reason(context.get(), crs.wkt, logged));
  }
  proj_log_level(context.get(), PJ_LOG_NONE);
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
