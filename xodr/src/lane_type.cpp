// Lane type names (OpenDRIVE 1.8 §9.5.3, e_laneType; 1.4-1.7 names kept where they differ) and
// which types vehicles drive on.

#include <array>
#include <utility>

#include "corsa/core/strings.h"
#include "corsa/xodr/parser.h"

namespace corsa::xodr {
namespace {

constexpr std::array<std::pair<std::string_view, LaneType>, 32> kNames = {{
    {"none", LaneType::kNone},           {"driving", LaneType::kDriving},
    {"stop", LaneType::kStop},           {"shoulder", LaneType::kShoulder},
    {"biking", LaneType::kBiking},       {"sidewalk", LaneType::kSidewalk},
    {"walking", LaneType::kWalking},     {"border", LaneType::kBorder},
    {"curb", LaneType::kCurb},           {"restricted", LaneType::kRestricted},
    {"parking", LaneType::kParking},     {"bidirectional", LaneType::kBidirectional},
    {"median", LaneType::kMedian},       {"special1", LaneType::kSpecial1},
    {"special2", LaneType::kSpecial2},   {"special3", LaneType::kSpecial3},
    {"roadWorks", LaneType::kRoadWorks}, {"tram", LaneType::kTram},
    {"rail", LaneType::kRail},           {"entry", LaneType::kEntry},
    {"exit", LaneType::kExit},           {"offRamp", LaneType::kOffRamp},
    {"onRamp", LaneType::kOnRamp},       {"connectingRamp", LaneType::kConnectingRamp},
    {"slipLane", LaneType::kSlipLane},   {"bus", LaneType::kBus},
    {"taxi", LaneType::kTaxi},           {"HOV", LaneType::kHov},
    {"shared", LaneType::kShared},       {"mwyEntry", LaneType::kEntry},  // OpenDRIVE 1.4 names
    {"mwyExit", LaneType::kExit},        {"other", LaneType::kOther},
}};

}  // namespace

LaneType lane_type_from_name(std::string_view name) {
  for (const auto& [text, type] : kNames) {
    if (corsa::iequals(text, name)) {
      return type;
    }
  }
  return LaneType::kOther;
}

std::string_view lane_type_name(LaneType type) {
  if (type == LaneType::kOther) {
    return "none";
  }
  for (const auto& [text, value] : kNames) {
    if (value == type) {
      return text;
    }
  }
  return "none";
}

bool is_drivable(LaneType type) {
  switch (type) {
    case LaneType::kDriving:
    case LaneType::kEntry:
    case LaneType::kExit:
    case LaneType::kOffRamp:
    case LaneType::kOnRamp:
    case LaneType::kConnectingRamp:
    case LaneType::kSlipLane:
    case LaneType::kBidirectional:
    case LaneType::kBus:
    case LaneType::kTaxi:
    case LaneType::kHov:
      return true;
    default:
      return false;
  }
}

}  // namespace corsa::xodr
