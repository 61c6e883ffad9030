// The 0.9-to-1.0 mapping (osc09_rewriter.h) of global actions: 0.9's SetEnvironment and its
// Environment (TimeOfDay of Time and Date, Precipitation type, RoadCondition frictionScale).

#include <charconv>
#include <cstdio>

#include "osc09_rewriter.h"

namespace corsa::xosc {
namespace {

template <typename T>
bool number_of(const Element* e, const char* attribute, T* out) {
  const char* text = e == nullptr ? nullptr : e->Attribute(attribute);
  if (text == nullptr) return false;
  const std::string_view view(text);
  const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), *out);
  return error == std::errc() && end == view.data() + view.size();
}

}  // namespace

void Osc09Rewriter::global_action(Element* e) {
  rename(e, "GlobalAction");
  for (Element* set : osc09_children(e, "SetEnvironment")) {
    rename(set, "EnvironmentAction");
    for (Element* environment : osc09_children(set, "Environment")) this->environment(environment);
  }
}

// 0.9's TimeOfDay held a Time (hour, min, sec) and a Date (day, month, year), 1.0's one dateTime.
// Values that are not plain numbers (a parameter) are left for the reader to refuse at the
// element.
void Osc09Rewriter::environment(Element* e) {
  for (Element* time_of_day : osc09_children(e, "TimeOfDay")) {
    Element* time = time_of_day->FirstChildElement("Time");
    Element* date = time_of_day->FirstChildElement("Date");
    int hour = 0, minute = 0, day = 0, month = 0, year = 0;
    double second = 0.0;
    if (!number_of(time, "hour", &hour) || !number_of(time, "min", &minute) ||
        !number_of(time, "sec", &second) || !number_of(date, "day", &day) ||
        !number_of(date, "month", &month) || !number_of(date, "year", &year) || second < 0.0 ||
        second >= 60.0) {
      continue;
    }
    char text[64];
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d", year, month, day, hour,
                  minute, static_cast<int>(second));
    note("TimeOfDay Time/Date");
    time_of_day->SetAttribute("dateTime", text);
    time_of_day->DeleteChild(time);
    time_of_day->DeleteChild(date);
  }
  for (Element* weather : osc09_children(e, "Weather")) {
    for (Element* p : osc09_children(weather, "Precipitation")) {
      if (p->Attribute("type") != nullptr) note("Precipitation type");
      move_attribute(p, "type", "precipitationType");
    }
  }
  for (Element* road : osc09_children(e, "RoadCondition")) {
    if (road->Attribute("frictionScale") != nullptr) note("RoadCondition frictionScale");
    move_attribute(road, "frictionScale", "frictionScaleFactor");
  }
}

}  // namespace corsa::xosc
