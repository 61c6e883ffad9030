#include "corsa/xodr/palette.h"

namespace corsa::xodr {

Rgb lane_type_color(LaneType type) {
  if (is_drivable(type)) {
    // Reserved lanes a reddish asphalt, every other drivable lane asphalt grey.
    const bool reserved =
        type == LaneType::kBus || type == LaneType::kTaxi || type == LaneType::kHov;
    return reserved ? Rgb{112, 96, 96} : Rgb{96, 98, 104};
  }
  switch (type) {
    case LaneType::kSidewalk:
    case LaneType::kWalking:
      return {206, 200, 188};
    case LaneType::kCurb:
      return {176, 174, 170};
    case LaneType::kShoulder:
    case LaneType::kStop:
      return {140, 140, 138};
    case LaneType::kBorder:
      return {160, 156, 148};
    case LaneType::kBiking:
      return {164, 100, 88};
    case LaneType::kParking:
      return {122, 112, 138};
    case LaneType::kRestricted:
      return {150, 120, 116};
    case LaneType::kMedian:
      return {132, 160, 112};
    case LaneType::kTram:
    case LaneType::kRail:
      return {136, 112, 92};
    case LaneType::kRoadWorks:
      return {196, 140, 64};
    case LaneType::kShared:
      return {128, 124, 132};
    case LaneType::kSpecial1:
    case LaneType::kSpecial2:
    case LaneType::kSpecial3:
    case LaneType::kOther:
      return {150, 146, 150};
    default:  // kNone; the drivable types are coloured above
      break;
  }
  return {168, 168, 160};
}

Rgb mark_color_rgb(MarkColor color) {
  switch (color) {
    case MarkColor::kYellow:
      return {240, 196, 40};
    case MarkColor::kBlue:
      return {60, 110, 220};
    case MarkColor::kGreen:
      return {60, 170, 80};
    case MarkColor::kRed:
      return {210, 50, 40};
    case MarkColor::kOrange:
      return {240, 140, 30};
    case MarkColor::kViolet:
      return {150, 80, 190};
    case MarkColor::kBlack:
      return {20, 20, 20};
    case MarkColor::kWhite:
    case MarkColor::kNone:
      break;
  }
  return {246, 246, 242};
}

}  // namespace corsa::xodr
