// OpenDRIVE signals (OpenDRIVE 1.8 §14) drawn as traffic lights and signs. Traffic lights:
// dynamic signals and the German 1000xxx types; vertical three-light heads in Germany and for
// CARLA's "OpenDRIVE" country, horizontal heads in Korea (also the lights the NGII import writes);
// their bulbs follow the scenario's TrafficSignalState (WorldSnapshot::signals). Signs: the common
// German (StVO) and Korean types by shape, colours and symbol; any other type a generic white sign
// with one located warning. Signals that stand for road markings are painted on the road
// (world_markings.cpp).

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "corsa/core/strings.h"
#include "scalar_math.h"
#include "world_build.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

const Color kRed = linear_rgb(196, 22, 28);
const Color kWhite = linear_rgb(236, 236, 232);
const Color kBlue = linear_rgb(0, 82, 164);
const Color kYellow = linear_rgb(250, 200, 0);
const Color kBlack = linear_rgb(18, 18, 18);

struct SignSpec {
  SignFace face;
  double width = 0.6;
  double height = 0.6;
};

SignFace face(SignShape shape, Color fill, Color border, double border_width, SignSymbol symbol,
              Color symbol_color, int number = 0) {
  SignFace f;
  f.shape = shape;
  f.fill = fill;
  f.border = border;
  f.border_width = border_width;
  f.symbol = symbol;
  f.symbol_color = symbol_color;
  f.number = number;
  return f;
}

int type_number(const std::string& type) {
  const auto v = parse_int(type);
  return v ? static_cast<int>(*v) : -1;
}

/// German signs (StVO catalogue numbers), also used for CARLA's country "OpenDRIVE".
std::optional<SignSpec> german_sign(int type, const xodr::Signal& s) {
  const int speed = s.value ? static_cast<int>(std::lround(*s.value)) : 0;
  SignSpec spec;
  if (type == 205) {
    spec.face = face(SignShape::kTriangleDown, kWhite, kRed, 0.2, SignSymbol::kNone, kBlack);
    spec.width = spec.height = 0.9;
  } else if (type == 206) {
    spec.face = face(SignShape::kOctagon, kRed, kWhite, 0.06, SignSymbol::kStopText, kWhite);
  } else if (type == 274 || type == 275) {
    spec.face =
        type == 274
            ? face(SignShape::kCircle, kWhite, kRed, 0.17, SignSymbol::kNumber, kBlack, speed)
            : face(SignShape::kCircle, kBlue, kWhite, 0.05, SignSymbol::kNumber, kWhite, speed);
  } else if (type == 267) {
    spec.face = face(SignShape::kCircle, kRed, kWhite, 0.05, SignSymbol::kBar, kWhite);
  } else if (type == 250 || type == 276 || type == 277 || type == 251 || type == 253 ||
             type == 254 || type == 260 || type == 262 || type == 265) {
    spec.face = face(SignShape::kCircle, kWhite, kRed, 0.17, SignSymbol::kNone, kBlack);
  } else if (type == 278 || type == 280 || type == 281 || type == 282) {
    spec.face = face(SignShape::kCircle, kWhite, kBlack, 0.03, SignSymbol::kDiagonal, kBlack);
  } else if (type == 283 || type == 286) {
    spec.face = face(SignShape::kCircle, kBlue, kRed, 0.15,
                     type == 283 ? SignSymbol::kCross : SignSymbol::kDiagonal, kRed);
  } else if (type >= 209 && type <= 222) {
    const SignSymbol arrow = s.subtype == "10"   ? SignSymbol::kArrowRight
                             : s.subtype == "20" ? SignSymbol::kArrowLeft
                                                 : SignSymbol::kArrowUp;
    spec.face = face(SignShape::kCircle, kBlue, kWhite, 0.04, arrow, kWhite);
  } else if (type >= 237 && type <= 244) {
    spec.face = face(SignShape::kCircle, kBlue, kWhite, 0.04, SignSymbol::kPerson, kWhite);
  } else if (type == 306) {
    spec.face = face(SignShape::kDiamond, kWhite, kBlack, 0.04, SignSymbol::kInnerDiamond, kYellow);
  } else if (type == 307) {
    spec.face = face(SignShape::kDiamond, kWhite, kBlack, 0.04, SignSymbol::kDiagonal, kBlack);
  } else if (type == 301) {
    spec.face = face(SignShape::kTriangleUp, kWhite, kRed, 0.2, SignSymbol::kArrowUp, kBlack);
    spec.width = spec.height = 0.9;
  } else if (type >= 101 && type <= 157) {
    spec.face =
        face(SignShape::kTriangleUp, kWhite, kRed, 0.2,
             type == 133 || type == 134 ? SignSymbol::kPerson : SignSymbol::kExclamation, kBlack);
    spec.width = spec.height = 0.9;
  } else if (type == 350) {
    spec.face = face(SignShape::kSquare, kBlue, kWhite, 0.04, SignSymbol::kPerson, kWhite);
  } else if (type == 310 || type == 311) {
    spec.face = face(SignShape::kRectangle, kYellow, kBlack, 0.05, SignSymbol::kNone, kBlack);
    spec.width = 1.2;
    spec.height = 0.6;
  } else if (type == 314 || type == 224) {
    spec.face = face(SignShape::kSquare, kBlue, kWhite, 0.04, SignSymbol::kNone, kWhite);
  } else {
    return std::nullopt;
  }
  return spec;
}

/// Korean signs (road sign catalogue: 1xx caution, 2xx regulation, 3xx instruction, 4xx
/// auxiliary).
std::optional<SignSpec> korean_sign(int type, const xodr::Signal& s) {
  const int speed = s.value ? static_cast<int>(std::lround(*s.value)) : 0;
  SignSpec spec;
  if (type >= 100 && type < 200) {
    spec.face =
        face(SignShape::kTriangleUp, kYellow, kRed, 0.17,
             type == 132 || type == 133 ? SignSymbol::kPerson : SignSymbol::kExclamation, kBlack);
    spec.width = spec.height = 0.9;
  } else if (type == 224) {
    spec.face = face(SignShape::kCircle, kWhite, kRed, 0.17, SignSymbol::kNumber, kBlack, speed);
  } else if (type == 225) {
    spec.face = face(SignShape::kCircle, kBlue, kWhite, 0.04, SignSymbol::kNumber, kWhite, speed);
  } else if (type == 227) {
    spec.face = face(SignShape::kOctagon, kRed, kWhite, 0.06, SignSymbol::kStopText, kWhite);
  } else if (type == 226 || type == 228) {
    spec.face = face(SignShape::kTriangleDown, kWhite, kRed, 0.2, SignSymbol::kNone, kBlack);
    spec.width = spec.height = 0.9;
  } else if (type >= 200 && type < 300) {
    spec.face = face(SignShape::kCircle, kWhite, kRed, 0.17, SignSymbol::kNone, kBlack);
  } else if (type == 321 || type == 322) {
    spec.face = face(SignShape::kSquare, kBlue, kWhite, 0.04, SignSymbol::kPerson, kWhite);
  } else if (type >= 300 && type < 400) {
    spec.face = face(SignShape::kCircle, kBlue, kWhite, 0.04, SignSymbol::kArrowUp, kWhite);
  } else if (type >= 400 && type < 500) {
    spec.face = face(SignShape::kRectangle, kWhite, kBlack, 0.05, SignSymbol::kNone, kBlack);
    spec.width = 0.6;
    spec.height = 0.3;
  } else {
    return std::nullopt;
  }
  return spec;
}

/// True for a signal `corsa convert ngii` made from a Korean NGII C1 traffic light: it writes the
/// German catalogue's numbers with country "OpenDRIVE" so that every reader knows the type, and
/// keeps the NGII layer in the signal's userData.
bool from_korean_layer(const xodr::Signal& s) {
  return std::any_of(s.user_data.begin(), s.user_data.end(), [](const xodr::UserData& d) {
    return d.code.rfind("ngii:C1_TRAFFICLIGHT", 0) == 0;
  });
}

bool is_traffic_light(const xodr::Signal& s) {
  const int type = type_number(s.type);
  return s.dynamic || (type >= 1000000 && type < 1001000);
}

}  // namespace

bool is_korean(const std::string& country) {
  const std::string c = to_lower(country);
  return c == "kr" || c == "kor" || c == "korea";
}

ObjectInfo signal_info(const xodr::Signal& s) {
  ObjectInfo info;
  info.signal_id = s.id;
  info.country = s.country;
  info.type = s.type;
  info.subtype = s.subtype;
  return info;
}

void build_signals(WorldBuild& w) {
  const xodr::Map& map = w.map;
  const std::string& file = map.data().source_file;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    for (const xodr::Signal& s : road.signals) {
      const double along = std::clamp(s.s, 0.0, road.length);
      const xodr::WorldPose p = map.world_pose(r, along, s.t);
      // "+": for traffic driving towards +s, so the face looks back along -s.
      const double facing = p.h + s.h_offset + (s.orientation == "-" ? 0.0 : kPi);
      const Rigid pose = rigid_from_pose(p.x, p.y, p.z, facing, 0.0, 0.0);
      ObjectInfo info = signal_info(s);
      info.value = s.value;
      info.text = s.text;
      if (is_traffic_light(s)) {
        const bool korean = is_korean(s.country) || from_korean_layer(s);
        const double head = s.height > 0.3 ? std::min(s.height, 1.4) : (korean ? 0.4 : 0.95);
        double bottom = s.z_offset;
        if (bottom < 1.5) {
          w.diagnostics.add_once(
              "signal-low-light",
              make_warning(file, s.line,
                           "traffic light " + s.id + " has zOffset " + format_fixed(s.z_offset, 2) +
                               " m (below 1.5 m); traffic lights are drawn with their head at "
                               "2.2 m on a post"));
          bottom = 2.2;
        }
        info.kind = "traffic_light";
        w.place(make_traffic_light(korean ? SignalLayout::kHorizontal4 : SignalLayout::kVertical3,
                                   bottom, head),
                pose, "traffic light " + s.id, info, s.id);
        ++w.report.traffic_lights;
        continue;
      }
      if (build_signal_marking(w, r, s)) {
        continue;
      }
      const int type = type_number(s.type);
      std::optional<SignSpec> spec =
          is_korean(s.country) ? korean_sign(type, s) : german_sign(type, s);
      if (!spec) {
        w.diagnostics.add_once(
            "signal-type:" + s.country + ":" + s.type,
            make_warning(file, s.line,
                         "signal type '" + s.type + "' (country '" + s.country +
                             "') is not one Corsa draws; drawn as a generic sign"));
        spec = SignSpec{face(SignShape::kRectangle, kWhite, linear_rgb(90, 90, 90), 0.06,
                             SignSymbol::kExclamation, kBlack),
                        0.6, 0.6};
      }
      const double width = s.width > 0.1 ? s.width : spec->width;
      const double height = s.height > 0.1 ? s.height : spec->height;
      const double bottom = s.z_offset >= 1.0 ? s.z_offset : 2.0;
      info.kind = "traffic_sign";
      w.place(make_sign(spec->face, width, height, bottom,
                        "sign " + s.country + " " + s.type + " " + s.subtype + " " +
                            (s.value ? format_double(*s.value) : std::string())),
              pose, "traffic sign " + s.id, info);
      ++w.report.signs;
    }
  }
}

}  // namespace corsa::sensors::detail
