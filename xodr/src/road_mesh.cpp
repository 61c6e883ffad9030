// build_road_mesh / build_road_marks: road by road, section by section, the adaptive samples,
// the lane surfaces and the road marks (mesh_section.cpp, mesh_lanes.cpp, mesh_marks.cpp).

#include "corsa/xodr/road_mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/road_marks.h"
#include "mesh_builder.h"

namespace corsa::xodr {
namespace {

/// Triangles with a smaller area seen from above (m²) are degenerate and left out.
constexpr double kMinArea = 1e-12;
/// Across a jump and in road marks, thinner triangles (m) are slivers, not surface.
constexpr double kMinSliverHeight = 1e-3;
/// Sections shorter than this (m) have no surface.
constexpr double kMinSectionLength = 1e-6;

void check_options(const MeshOptions& options) {
  if (!(options.tolerance >= 1e-4) || !std::isfinite(options.tolerance)) {
    throw std::invalid_argument("mesh tolerance must be a finite number of at least 0.0001 m");
  }
  if (!(options.max_segment >= 0.0) || !(options.mark_lift >= 0.0)) {
    throw std::invalid_argument("mesh max_segment and mark_lift must not be negative");
  }
}

/// Calls `visit(view, samples)` for every lane section with a length, in road and section order.
template <typename Visit>
void for_each_section(const Map& map, const MeshOptions& options, Visit visit) {
  for (uint32_t road = 0; road < map.road_count(); ++road) {
    const auto sections = static_cast<uint32_t>(map.road(road).lane_sections.size());
    for (uint32_t section = 0; section < sections; ++section) {
      const detail::SectionView view(map, road, section);
      if (view.s1() - view.s0() < kMinSectionLength) {
        continue;
      }
      const detail::SectionSamples samples =
          detail::sample_section(view, options.tolerance, options.max_segment);
      visit(view, samples);
    }
  }
}

/// Refuses vertices past the range of doubles (widths like 1e308 m summed across lanes): a mesh
/// file could not say where they are. Checks the vertices from `checked` on.
void check_finite(const Map& map, uint32_t road, const RoadMesh& mesh, size_t& checked) {
  for (; checked < mesh.vertices.size(); ++checked) {
    const Vec3& v = mesh.vertices[checked];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      const Road& r = map.road(road);
      throw corsa::InputError(corsa::make_error(
          map.data().source_file, r.line,
          "road '" + corsa::clip(r.id) +
              "': its surface reaches beyond the range of numbers (lane widths, offsets or "
              "elevation too large for a mesh)"));
    }
  }
}

}  // namespace

namespace detail {

uint32_t MeshBuilder::add_vertex(const Vec3& p, std::array<float, 2> lane) {
  mesh_.vertices.push_back(p);
  mesh_.lane_coords.push_back(lane);
  return static_cast<uint32_t>(mesh_.vertices.size() - 1);
}

void MeshBuilder::add_upward(uint32_t a, uint32_t b, uint32_t c, const TriangleInfo& info,
                             const Road* fold_road, double s) {
  const Vec3& pa = mesh_.vertices[a];
  const Vec3& pb = mesh_.vertices[b];
  const Vec3& pc = mesh_.vertices[c];
  const double area2 = (pb.x - pa.x) * (pc.y - pa.y) - (pb.y - pa.y) * (pc.x - pa.x);
  if (area2 > 2.0 * kMinArea) {
    if (fold_road == nullptr) {
      // Height over the longest side, seen from above.
      const double longest =
          std::max({std::hypot(pb.x - pa.x, pb.y - pa.y), std::hypot(pc.x - pb.x, pc.y - pb.y),
                    std::hypot(pa.x - pc.x, pa.y - pc.y)});
      if (area2 / longest < kMinSliverHeight) {
        return;
      }
    }
    add_any(a, b, c, info);
    return;
  }
  if (area2 < -2.0 * kMinArea && fold_road != nullptr) {
    const Road& road = *fold_road;
    std::string where = s >= 0.0 ? " near s=" + corsa::format_fixed(s, 2) : std::string();
    diagnostics_.add_once(
        "mesh fold " + road.id,
        corsa::make_warning(file_, road.line,
                            "road '" + road.id + "': a lane border or road mark" + where +
                                " folds over itself (it lies beyond the "
                                "centre of curvature); those triangles are "
                                "left out of the mesh"));
  }
}

void MeshBuilder::add_any(uint32_t a, uint32_t b, uint32_t c, const TriangleInfo& info) {
  mesh_.triangles.push_back({a, b, c});
  mesh_.info.push_back(info);
}

void MeshBuilder::compact() {
  std::vector<uint32_t> remap(mesh_.vertices.size(), UINT32_MAX);
  for (const auto& triangle : mesh_.triangles) {
    for (uint32_t v : triangle) {
      remap[v] = 0;
    }
  }
  uint32_t next = 0;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == 0) {
      mesh_.vertices[next] = mesh_.vertices[v];
      mesh_.lane_coords[next] = mesh_.lane_coords[v];
      remap[v] = next++;
    }
  }
  mesh_.vertices.resize(next);
  mesh_.lane_coords.resize(next);
  for (auto& triangle : mesh_.triangles) {
    for (uint32_t& v : triangle) {
      v = remap[v];
    }
  }
}

}  // namespace detail

RoadMesh build_road_mesh(const Map& map, const MeshOptions& options,
                         corsa::Diagnostics& diagnostics) {
  check_options(options);
  RoadMesh mesh;
  detail::MeshBuilder builder(mesh, diagnostics, map.data().source_file);
  std::vector<detail::SeamVertex> seam;
  std::vector<MarkLine> marks;
  uint32_t seam_road = UINT32_MAX;
  size_t checked = 0;
  for_each_section(map, options,
                   [&](const detail::SectionView& view, const detail::SectionSamples& samples) {
                     if (view.road_index() != seam_road) {
                       seam.clear();  // a new road: nothing to share with
                       seam_road = view.road_index();
                     }
                     detail::mesh_section_lanes(view, samples, options.tolerance, builder, seam);
                     if (options.road_marks) {
                       marks.clear();
                       detail::section_mark_lines(view, samples, options, diagnostics, marks);
                       for (const MarkLine& line : marks) {
                         detail::mesh_mark_line(line, builder);
                       }
                     }
                     check_finite(map, view.road_index(), mesh, checked);
                   });
  builder.compact();
  return mesh;
}

RoadMesh build_road_mesh(const Map& map, const MeshOptions& options) {
  corsa::Diagnostics ignored;
  return build_road_mesh(map, options, ignored);
}

std::vector<MarkLine> build_road_marks(const Map& map, const MeshOptions& options,
                                       corsa::Diagnostics& diagnostics) {
  check_options(options);
  std::vector<MarkLine> marks;
  for_each_section(map, options,
                   [&](const detail::SectionView& view, const detail::SectionSamples& samples) {
                     detail::section_mark_lines(view, samples, options, diagnostics, marks);
                   });
  return marks;
}

const char* mark_color_name(MarkColor color) {
  switch (color) {
    case MarkColor::kWhite:
      return "white";
    case MarkColor::kYellow:
      return "yellow";
    case MarkColor::kBlue:
      return "blue";
    case MarkColor::kGreen:
      return "green";
    case MarkColor::kRed:
      return "red";
    case MarkColor::kOrange:
      return "orange";
    case MarkColor::kViolet:
      return "violet";
    case MarkColor::kBlack:
      return "black";
    case MarkColor::kNone:
      break;
  }
  return "none";
}

}  // namespace corsa::xodr
