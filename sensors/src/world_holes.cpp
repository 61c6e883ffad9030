// Paving of the holes in junctions (corsa/xodr/junction_holes.h): where a map's connecting roads
// leave a small or narrow patch uncovered between them, bordered only by the junction's roadway,
// the street is asphalt, not grass. The paving is plain road surface (class road, the road's
// look, no markings) a hair under the roads around it, so it shows only where they leave a gap.
// Islands (wide and large holes), kerbed holes and holes with something standing in them keep
// the ground.

#include "corsa/xodr/junction_holes.h"
#include "world_build.h"

namespace corsa::sensors::detail {

void build_junction_paving(WorldBuild& w, const xodr::RoadMesh& road) {
  StaticMesh paving;
  paving.name = "junction paving";
  paving.classes = {SemanticClass::kRoad};
  for (const xodr::JunctionHole& hole : xodr::find_junction_holes(w.map, road)) {
    ++w.report.junction_holes;
    if (hole.kind != xodr::HoleKind::kPaved) {
      continue;
    }
    ++w.report.junction_holes_paved;
    w.report.junction_paved_area += hole.area;
    const auto base = static_cast<uint32_t>(paving.vertices.size());
    paving.vertices.insert(paving.vertices.end(), hole.vertices.begin(), hole.vertices.end());
    for (const auto& t : hole.triangles) {
      paving.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }
  if (!paving.triangles.empty()) {
    w.scene.add_static_mesh(std::move(paving));
  }
}

}  // namespace corsa::sensors::detail
