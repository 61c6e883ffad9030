#include "centre_gaps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace corsa::test {
namespace {

constexpr double kPairReach = 1.6;    // m: farthest opposing centre mark read as the pair
constexpr double kInside = 0.3;       // m sampled beyond each mark, inside its lane
constexpr double kSampleStep = 0.02;  // m between samples across the strip
constexpr double kGapLimit = 0.05;    // m

struct Pt {
  double x = 0.0, y = 0.0;
};

struct CentreMark {
  const ngii::SurfaceMark* mark = nullptr;
  std::vector<Pt> points;  ///< map coordinates
  std::vector<double> u;   ///< arc length at each point
};

/// Nearest point of `line` to q: distance, signed lateral (+ left of its direction), direction
/// there, and whether the foot is inside (not an end reached from beyond it).
struct LineFoot {
  double distance = 1e300;
  double lateral = 0.0;
  Pt direction;
  bool inside = false;
};

LineFoot foot_of(const std::vector<Pt>& line, Pt q) {
  LineFoot best;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double dx = line[i + 1].x - line[i].x, dy = line[i + 1].y - line[i].y;
    const double len = std::hypot(dx, dy);
    if (len <= 0.0) {
      continue;
    }
    const double f = ((q.x - line[i].x) * dx + (q.y - line[i].y) * dy) / (len * len);
    const double c = std::clamp(f, 0.0, 1.0);
    const double d = std::hypot(q.x - line[i].x - c * dx, q.y - line[i].y - c * dy);
    if (d < best.distance) {
      best.distance = d;
      best.lateral = (dx * (q.y - line[i].y) - dy * (q.x - line[i].x)) / len;
      best.direction = {dx / len, dy / len};
      best.inside = !((i == 0 && f < 0.0) || (i + 2 == line.size() && f > 1.0));
    }
  }
  return best;
}

/// Point and unit direction at arc length s of a mark.
void point_at(const CentreMark& m, double s, Pt& p, Pt& d) {
  size_t i = 1;
  while (i + 1 < m.u.size() && m.u[i] < s) {
    ++i;
  }
  const Pt a = m.points[i - 1], b = m.points[i];
  const double len = m.u[i] - m.u[i - 1];
  const double f = len > 0.0 ? (s - m.u[i - 1]) / len : 0.0;
  p = {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)};
  d = len > 0.0 ? Pt{(b.x - a.x) / len, (b.y - a.y) / len} : Pt{1.0, 0.0};
}

bool is_centre(const ngii::SurfaceMark& mark) {
  return ((!mark.type.empty() && mark.type[0] == '1') || mark.kind == "501") &&
         !mark.right_link.empty() && mark.right_link != mark.left_link;
}

}  // namespace

CentreGapFigures centre_gaps(const ngii::Layers& layers, const xodr::Map& map) {
  const double ox = map.data().header.offset_x, oy = map.data().header.offset_y;
  std::vector<CentreMark> marks;
  for (const auto& mark : layers.marks) {
    if (!is_centre(mark) || mark.points.size() < 2) {
      continue;
    }
    CentreMark m{&mark, {}, {}};
    for (const auto& p : mark.points) {
      const Pt q{p.x - ox, p.y - oy};
      const double step =
          m.points.empty() ? 0.0 : std::hypot(q.x - m.points.back().x, q.y - m.points.back().y);
      if (!m.points.empty() && step <= 1e-6) {
        continue;
      }
      m.u.push_back(m.u.empty() ? 0.0 : m.u.back() + step);
      m.points.push_back(q);
    }
    if (m.points.size() >= 2) {
      marks.push_back(std::move(m));
    }
  }
  std::map<std::string, std::vector<Pt>> links;
  for (const auto& link : layers.links) {
    auto& line = links[link.id];
    for (const auto& p : link.points) {
      line.push_back({p.x - ox, p.y - oy});
    }
  }
  // Whether links a and b run opposite ways beside point v (a mark naming both sides may as
  // well part two lanes of one direction).
  const auto opposed = [&](const std::string& a, const std::string& b, Pt v) {
    const auto la = links.find(a), lb = links.find(b);
    if (la == links.end() || lb == links.end()) {
      return false;
    }
    const LineFoot fa = foot_of(la->second, v), fb = foot_of(lb->second, v);
    return fa.distance < 10.0 && fb.distance < 10.0 &&
           fa.direction.x * fb.direction.x + fa.direction.y * fb.direction.y < -0.8;
  };
  CentreGapFigures out;
  xodr::LocateOptions options;
  options.max_distance = 1.0;
  for (const CentreMark& m : marks) {
    for (double s = 1.0; s < m.u.back() - 1.0 + 1e-9; s += 1.0) {
      Pt v, d;
      point_at(m, s, v, d);
      // The opposing mark: left of this one (its link lies on its right), running the other way.
      double width = -1.0;
      if (opposed(m.mark->right_link, m.mark->left_link, v)) {
        width = 0.0;  // one mark naming both directions' links
      }
      for (const CentreMark& o : marks) {
        if (&o == &m || o.mark->right_link == m.mark->right_link) {
          continue;
        }
        const LineFoot f = foot_of(o.points, v);
        // o runs the other way with its own link on its right, so v lies on o's left.
        if (!f.inside || f.distance > kPairReach ||
            f.direction.x * d.x + f.direction.y * d.y > -0.8 || f.lateral < -1e-3) {
          continue;
        }
        if (width < 0.0 || f.distance < width) {
          width = f.distance;
        }
      }
      if (width < 0.0) {
        continue;
      }
      ++out.stations;
      const Pt n{-d.y, d.x};  // left of the mark, towards the opposing road
      double run = 0.0, longest = 0.0;
      for (double a = -kInside; a <= width + kInside + 1e-9; a += kSampleStep) {
        const auto at = map.locate(v.x + a * n.x, v.y + a * n.y, options);
        if (at && at->distance <= 1e-6) {
          run = 0.0;
        } else {
          run += kSampleStep;
          longest = std::max(longest, run);
        }
      }
      if (longest > kGapLimit) {
        ++out.over;
        if (std::getenv("CORSA_MEASURE_LIST") != nullptr) {
          std::fprintf(stderr,
                       "centre gap %.2f m at mark %s (s %.0f, %.2f m to its pair; map x %.1f y "
                       "%.1f)\n",
                       longest, m.mark->id.c_str(), s, width, v.x, v.y);
        }
      }
      if (longest > out.max) {
        out.max = longest;
        out.worst = m.mark->id;
      }
    }
  }
  return out;
}

}  // namespace corsa::test
