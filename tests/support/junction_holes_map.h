#pragma once

// A hand-written map of small junctions whose connecting roads enclose holes of known size and
// kind: each junction is a square or rectangular ring of four straight connecting roads (two
// 3.5 m lanes each, the left one inside the ring) with an incoming road ending at its first
// corner, so the ring's inside, shrunk by one lane on every side, is a hole.

#include <cstdio>
#include <string>

namespace corsa::test {

struct HoleRing {
  std::string id;   ///< junction id; its roads are ID1..ID4 and the incoming road IDin
  double x0 = 0.0;  ///< m, first corner
  double y0 = 0.0;
  double sx = 8.0;  ///< m, ring size along x and y (reference lines)
  double sy = 8.0;
  std::string inner = "driving";  ///< type of the first road's inside lane
  bool pole = false;              ///< a pole object standing in the middle of the hole
  std::string boundary;           ///< the junction's <boundary> content, if any
};

/// A ring at x0 (y0 0) of sx by sy metres, all its lanes driving, nothing in it.
inline HoleRing hole_ring(const std::string& id, double x0, double sx = 8.0, double sy = 8.0) {
  HoleRing ring;
  ring.id = id;
  ring.x0 = x0;
  ring.sx = sx;
  ring.sy = sy;
  return ring;
}

inline std::string hole_ring_xodr(const HoleRing& ring) {
  auto num = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6f", v);
    return std::string(text);
  };
  auto lanes = [](const std::string& inner) {
    return R"(<lanes><laneSection s="0"><left><lane id="1" type=")" + inner +
           R"("><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<center><lane id="0" type="none"/></center><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>)";
  };
  auto road = [&](const std::string& id, const std::string& junction, double x, double y,
                  double hdg, double length, const std::string& inner, const std::string& objects,
                  const std::string& link = "") {
    return R"(<road id=")" + id + R"(" length=")" + num(length) + R"(" junction=")" + junction +
           R"(">)" + link + R"(<planView><geometry s="0" x=")" + num(x) + R"(" y=")" + num(y) +
           R"(" hdg=")" + num(hdg) + R"(" length=")" + num(length) +
           R"("><line/></geometry></planView>)" + lanes(inner) + "<objects>" + objects +
           "</objects></road>\n";
  };
  const double pi = 3.14159265358979323846;
  const std::string& j = ring.id;
  const std::string pole =
      ring.pole ? R"(<object id=")" + j + R"(pole" type="pole" s=")" + num(0.5 * ring.sx) +
                      R"(" t=")" + num(0.5 * ring.sy) +
                      R"(" zOffset="0" hdg="0" orientation="none" radius="0.1" height="3"/>)"
                : "";
  std::string text;
  text += road(j + "in", "-1", ring.x0 - 20.0, ring.y0, 0.0, 20.0, "driving", "",
               R"(<link><successor elementType="junction" elementId=")" + j + R"("/></link>)");
  text += road(j + "1", j, ring.x0, ring.y0, 0.0, ring.sx, ring.inner, pole,
               R"(<link><predecessor elementType="road" elementId=")" + j +
                   R"(in" contactPoint="end"/></link>)");
  text += road(j + "2", j, ring.x0 + ring.sx, ring.y0, 0.5 * pi, ring.sy, "driving", "");
  text += road(j + "3", j, ring.x0 + ring.sx, ring.y0 + ring.sy, pi, ring.sx, "driving", "");
  text += road(j + "4", j, ring.x0, ring.y0 + ring.sy, 1.5 * pi, ring.sy, "driving", "");
  text += R"(<junction id=")" + j + R"("><connection id="0" incomingRoad=")" + j +
          R"(in" connectingRoad=")" + j +
          R"(1" contactPoint="start"><laneLink from="-1" to="-1"/></connection>)";
  if (!ring.boundary.empty()) {
    text += "<boundary>" + ring.boundary + "</boundary>";
  }
  text += "</junction>\n";
  return text;
}

/// The whole document around some rings.
inline std::string hole_rings_document(const std::string& rings) {
  return R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="8"/>
)" + rings +
         "</OpenDRIVE>\n";
}

}  // namespace corsa::test
