// NGII feature layers -> OpenDRIVE (see feature_layers.h).

#include "feature_layers.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>

#include "reference_line.h"
#include "road_frame.h"

namespace corsa::ngii::detail {
namespace {

/// What a C3 Type code stands for: OpenDRIVE object type, a name and a height (m).
struct BarrierKind {
  const char* type;
  const char* name;
  double height;
};

BarrierKind barrier_kind(const std::string& code) {
  if (code == "2") return {"railing", "guard rail", 0.8};
  if (code == "3") return {"barrier", "concrete barrier", 0.8};
  if (code == "4") return {"barrier", "kerb", 0.15};
  if (code == "5") return {"railing", "pedestrian fence", 1.0};
  if (code == "6") return {"barrier", "median opening", 0.8};
  if (code == "7") return {"barrier", "temporary barrier", 0.8};
  if (code == "8") return {"barrier", "wall", 2.0};
  return {"barrier", "barrier", 0.8};
}

class FeaturePlacer {
 public:
  FeaturePlacer(xodr::MapData& map, const std::vector<LinkPlacement>& placements,
                const Origin& origin)
      : map_(map), origin_(origin), frames_(map.roads.size()) {
    for (size_t r = 0; r < map.roads.size(); ++r) {
      road_index_.emplace(map.roads[r].id, r);
    }
    for (const LinkPlacement& p : placements) {
      roads_of_link_[p.link_id].push_back(road_index_.at(p.road_id));
    }
  }

  /// B2 stop lines (Kind 530), which run across the lanes rather than along them: roadMark
  /// objects, the line widened to 0.4 m as a closed outline.
  size_t stop_lines(const std::vector<SurfaceMark>& marks) {
    constexpr double kHalf = 0.2;  // m: half the width of the painted stop line
    size_t made = 0;
    for (const SurfaceMark& mark : marks) {
      if (mark.kind != "530" || mark.points.size() < 2) {
        continue;
      }
      Feature line;
      line.id = mark.id;
      line.points = mark.points;
      const Point3 c = centroid(line.points);
      const auto road = road_for(line, local(c));
      if (!road) {
        continue;
      }
      const Point3& a = mark.points.front();
      const Point3& b = mark.points.back();
      const Vec2 d = local(b) - local(a);
      if (norm(d) < 0.1) {
        continue;
      }
      const Vec2 n = (kHalf / norm(d)) * Vec2{-d.y, d.x};
      const std::vector<Point3> ring{{a.x + n.x, a.y + n.y, a.z},
                                     {b.x + n.x, b.y + n.y, b.z},
                                     {b.x - n.x, b.y - n.y, b.z},
                                     {a.x - n.x, a.y - n.y, a.z}};
      const RoadFrame& f = frame(*road);
      const RoadFrame::Position p = f.project(local(c));
      xodr::Object object;
      object.id = mark.id;
      object.name = "stop line";
      object.type = "roadMark";
      object.subtype = "stopLine";
      object.s = p.s;
      object.t = p.t;
      object.outlines.push_back(outline(ring, f, true, 0.0));
      object.user_data.push_back(xodr::UserData{"ngii:B2_SURFACELINEMARK", mark.id});
      map_.roads[*road].objects.push_back(std::move(object));
      ++made;
    }
    return made;
  }

  FeatureCounts run(const std::vector<Feature>& features) {
    FeatureCounts counts;
    for (const Feature& feature : features) {
      switch (feature.layer) {
        case FeatureLayer::kSafetySign:
          counts.signals += sign(feature);
          break;
        case FeatureLayer::kSection:
          counts.structures += section(feature);
          break;
        case FeatureLayer::kBarrier:
          counts.objects += barrier(feature);
          break;
        default:
          counts.objects += area_object(feature);
          break;
      }
    }
    return counts;
  }

 private:
  Vec2 local(const Point3& p) const { return {p.x - origin_.x, p.y - origin_.y}; }

  const RoadFrame& frame(size_t road) {
    if (!frames_[road]) {
      frames_[road] = std::make_unique<RoadFrame>(map_.roads[road]);
    }
    return *frames_[road];
  }

  /// The road a feature belongs to: one carrying its LinkID when it has one (the one nearest
  /// the point), else the nearest road; nothing farther than 30 m.
  std::optional<size_t> road_for(const Feature& feature, Vec2 point) {
    std::vector<size_t> candidates;
    if (const auto it = roads_of_link_.find(feature.link_id); it != roads_of_link_.end()) {
      candidates = it->second;
    } else {
      for (size_t r = 0; r < map_.roads.size(); ++r) {
        if (frame(r).box_distance(point) < 30.0) {
          candidates.push_back(r);
        }
      }
    }
    std::optional<size_t> best;
    double best_score = 1e300;
    for (const size_t r : candidates) {
      const RoadFrame::Position p = frame(r).project(point);
      const double score = std::abs(p.outside) * 10.0 + std::abs(p.t);
      if (score < best_score) {
        best_score = score;
        best = r;
      }
    }
    if (best && best_score > 30.0) {
      return std::nullopt;
    }
    return best;
  }

  /// Mean of the vertices (a polygon ring's repeated first vertex counted once).
  static Point3 centroid(const std::vector<Point3>& points) {
    size_t n = points.size();
    if (n > 1 && points.front().x == points.back().x && points.front().y == points.back().y &&
        points.front().z == points.back().z) {
      --n;
    }
    Point3 c;
    for (size_t i = 0; i < n; ++i) {
      c.x += points[i].x / static_cast<double>(n);
      c.y += points[i].y / static_cast<double>(n);
      c.z += points[i].z / static_cast<double>(n);
    }
    return c;
  }

  /// An outline of road corners (s, t, dz above the road's elevation) for the points.
  xodr::Outline outline(const std::vector<Point3>& points, const RoadFrame& f, bool closed,
                        double height) const {
    xodr::Outline outline;
    outline.closed = closed;
    const size_t n =
        closed && points.size() > 1 && norm(local(points.front()) - local(points.back())) < 1e-6
            ? points.size() - 1  // the ring's repeated first vertex
            : points.size();
    for (size_t i = 0; i < n; ++i) {
      const RoadFrame::Position p = f.project(local(points[i]));
      outline.corners.push_back(xodr::OutlineCorner{
          true, p.s, p.t, points[i].z - piecewise_value(f.road().elevation, p.s), height,
          static_cast<int>(i)});
    }
    return outline;
  }

  /// B1: a static signal at the sign's centre, on the road of the link it concerns.
  bool sign(const Feature& feature) {
    const Point3 c = centroid(feature.points);
    const auto road = road_for(feature, local(c));
    if (!road) {
      return false;
    }
    const RoadFrame& f = frame(*road);
    const RoadFrame::Position p = f.project(local(c));
    double z0 = 1e300, z1 = -1e300, w = 0.0;
    for (const Point3& q : feature.points) {
      z0 = std::min(z0, q.z);
      z1 = std::max(z1, q.z);
      for (const Point3& r : feature.points) {
        w = std::max(w, norm(local(q) - local(r)));
      }
    }
    xodr::Signal signal;
    signal.id = feature.id;
    signal.name = "safety sign " + feature.id + " (NGII B1 type " + feature.type + ")";
    signal.s = p.s;
    signal.t = p.t;
    signal.z_offset = z0 - piecewise_value(f.road().elevation, p.s);
    signal.orientation = "+";
    signal.dynamic = false;
    signal.country = "KR";
    // B1 Type: 1 caution, 2 instruction, 3 regulatory, 4 supplementary (the sign itself is not
    // coded in NGII data model 2020); a speed or weight limit is in Remark.
    signal.type = feature.type.empty() ? "-1" : feature.type;
    signal.subtype = "-1";
    char* end = nullptr;
    const double value = std::strtod(feature.remark.c_str(), &end);
    if (!feature.remark.empty() && end != nullptr && *end == '\0' && value > 0.0) {
      signal.value = value;
      signal.unit = "km/h";
    }
    signal.height = std::max(0.0, z1 - z0);
    signal.width = w;
    signal.user_data.push_back(xodr::UserData{"ngii:B1_SAFETYSIGN.Type", feature.type});
    map_.roads[*road].signals.push_back(std::move(signal));
    return true;
  }

  /// C3: a railing or barrier along the line, one object per road it runs beside.
  size_t barrier(const Feature& feature) {
    const BarrierKind kind = barrier_kind(feature.type);
    size_t made = 0;
    size_t i = 0;
    while (i < feature.points.size()) {
      const auto road = road_for(feature, local(feature.points[i]));
      std::vector<Point3> piece;
      for (; i < feature.points.size(); ++i) {
        const auto here = road_for(feature, local(feature.points[i]));
        if (here != road) {
          break;
        }
        piece.push_back(feature.points[i]);
      }
      if (!road || piece.size() < 2) {
        continue;
      }
      const RoadFrame& f = frame(*road);
      xodr::Object object;
      object.id = feature.id + (made > 0 ? "_" + std::to_string(made) : "");
      object.name = kind.name;
      object.type = kind.type;
      object.subtype = "NGII C3 type " + feature.type;
      object.height = kind.height;
      const RoadFrame::Position p = f.project(local(piece.front()));
      object.s = p.s;
      object.t = p.t;
      object.outlines.push_back(outline(piece, f, false, kind.height));
      object.user_data.push_back(xodr::UserData{"ngii:C3_VEHICLEPROTECTIONSAFETY", feature.id});
      map_.roads[*road].objects.push_back(std::move(object));
      ++made;
    }
    return made;
  }

  /// B3, C4, C6, A4, A5: an object with the feature's outline (a pole for C6).
  bool area_object(const Feature& feature) {
    const Point3 c = centroid(feature.points);
    const auto road = road_for(feature, local(c));
    if (!road) {
      return false;
    }
    const RoadFrame& f = frame(*road);
    const RoadFrame::Position p = f.project(local(c));
    xodr::Object object;
    object.id = feature.id;
    object.s = p.s;
    object.t = p.t;
    object.z_offset = c.z - piecewise_value(f.road().elevation, p.s);
    std::string code = "ngii:";
    double height = 0.0;
    switch (feature.layer) {
      case FeatureLayer::kSurfaceMark:
        code += "B3_SURFACEMARK";
        object.type = feature.type == "5" ? "crosswalk" : "roadMark";
        object.name = feature.type == "5" ? "crosswalk" : "arrow";
        object.subtype = feature.kind;
        break;
      case FeatureLayer::kSpeedBump:
        code += "C4_SPEEDBUMP";
        object.type = "obstacle";
        object.name = "speed bump";
        object.subtype = "speedBump";
        height = 0.1;
        break;
      case FeatureLayer::kPost:
        code += "C6_POSTPOINT";
        object.type = "pole";
        object.name = feature.type == "1" ? "signal post" : "sign post";
        object.radius = 0.1;
        object.height = feature.type == "1" ? 6.0 : 3.0;
        break;
      case FeatureLayer::kSubsidiary:
        code += "A4_SUBSIDIARYSECTION";
        object.type = "patch";
        object.name = feature.remark.empty() ? "subsidiary section" : feature.remark;
        object.subtype = feature.type;
        break;
      default:
        code += "A5_PARKINGLOT";
        object.type = "parkingSpace";
        object.name = "parking lot";
        object.subtype = feature.type;
        break;
    }
    object.z_offset = feature.layer == FeatureLayer::kPost ? object.z_offset : 0.0;
    if (feature.layer != FeatureLayer::kPost) {
      object.outlines.push_back(outline(feature.points, f, true, height));
      object.height = height;
      if (feature.layer == FeatureLayer::kSubsidiary) {
        object.outlines.back().fill_type = feature.type == "3" ? "pavement" : "asphalt";
      }
    }
    if (object.type == "crosswalk") {
      // Zebra stripes along the outline's first edge (B3 outlines the whole crosswalk).
      object.markings.push_back(xodr::ObjectMarking{"white", 0.5, 0.005, 0.5, 0.5, {0, 1}});
    }
    object.user_data.push_back(xodr::UserData{code, feature.id});
    map_.roads[*road].objects.push_back(std::move(object));
    return true;
  }

  /// A3 with RoadType 2-5: tunnel or bridge records over the s ranges where the road's
  /// reference line runs inside the polygon.
  size_t section(const Feature& feature) {
    if (feature.kind.size() != 1 || feature.kind[0] < '2' || feature.kind[0] > '5') {
      return 0;  // Kind 7 (protection zones) and ordinary road sections: nothing to record
    }
    std::vector<Vec2> ring;
    for (const Point3& p : feature.points) {
      ring.push_back(local(p));
    }
    const auto inside = [&](Vec2 q) {
      bool in = false;
      for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        if (((ring[i].y > q.y) != (ring[j].y > q.y)) &&
            q.x <
                (ring[j].x - ring[i].x) * (q.y - ring[i].y) / (ring[j].y - ring[i].y) + ring[i].x) {
          in = !in;
        }
      }
      return in;
    };
    size_t made = 0;
    for (size_t r = 0; r < map_.roads.size(); ++r) {
      xodr::Road& road = map_.roads[r];
      const RoadFrame& f = frame(r);
      if (f.box_distance(ring.front()) > 2000.0) {
        continue;
      }
      double start = -1.0;
      const int steps = std::max(1, static_cast<int>(road.length));
      std::vector<double> stations(static_cast<size_t>(steps) + 1);
      for (int k = 0; k <= steps; ++k) {
        stations[static_cast<size_t>(k)] = road.length * k / steps;
      }
      const std::vector<RefSample> refs = sample_reference(road.plan_view, stations);
      for (int k = 0; k <= steps; ++k) {
        const double s = stations[static_cast<size_t>(k)];
        const double t = 0.5 * (f.border(s, 0) + f.border(s, f.lane_count()));
        const double h = refs[static_cast<size_t>(k)].hdg;
        const RefSample& ref = refs[static_cast<size_t>(k)];
        const Vec2 q{ref.x - t * std::sin(h), ref.y + t * std::cos(h)};
        const bool in = inside(q);
        if (in && start < 0.0) {
          start = s;
        }
        if ((!in || k == steps) && start >= 0.0) {
          const double end = in ? s : road.length * (k - 1) / steps;
          if (end - start > 0.5) {
            const std::string id = feature.id + "_" + road.id;
            const char kind = feature.kind[0];
            if (kind == '2' || kind == '4') {
              road.tunnels.push_back(
                  xodr::Tunnel{id, kind == '2' ? "tunnel" : "underground road", start, end - start,
                               kind == '2' ? "standard" : "underpass", 1.0, 0.0});
            } else {
              road.bridges.push_back(xodr::Bridge{id, kind == '3' ? "bridge" : "overpass", start,
                                                  end - start, "concrete"});
            }
            ++made;
          }
          start = -1.0;
        }
      }
    }
    return made;
  }

  xodr::MapData& map_;
  const Origin& origin_;
  std::vector<std::unique_ptr<RoadFrame>> frames_;
  std::unordered_map<std::string, size_t> road_index_;
  std::unordered_map<std::string, std::vector<size_t>> roads_of_link_;
};

}  // namespace

FeatureCounts place_features(xodr::MapData& map, const std::vector<LinkPlacement>& placements,
                             const Layers& layers, const Origin& origin) {
  FeaturePlacer placer(map, placements, origin);
  FeatureCounts counts = placer.run(layers.features);
  counts.objects += placer.stop_lines(layers.marks);
  for (xodr::Road& road : map.roads) {
    std::stable_sort(road.objects.begin(), road.objects.end(),
                     [](const xodr::Object& a, const xodr::Object& b) { return a.s < b.s; });
    std::stable_sort(road.signals.begin(), road.signals.end(),
                     [](const xodr::Signal& a, const xodr::Signal& b) { return a.s < b.s; });
  }
  return counts;
}

}  // namespace corsa::ngii::detail
