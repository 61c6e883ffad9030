// Generated plants (sensors/src/vegetation.cpp): crowns with sky through them, smooth outward
// normals, the same plant from the same stream, lamp heads left clear.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include "corsa/sensors/scene.h"
#include "corsa/sensors/world.h"
#include "vegetation.h"
#include "world_fixture.h"

using namespace corsa::sensors;
using corsa::RandomStream;
using corsa::Vec3;
using detail::ArticulatedMesh;
using detail::TreeForm;

namespace {

const TreeForm kForms[] = {TreeForm::kRound, TreeForm::kSpreading, TreeForm::kColumnar,
                           TreeForm::kYoung, TreeForm::kSpruce,    TreeForm::kPine};

ArticulatedMesh tree(TreeForm form, uint64_t seed, std::span<const detail::Clearance> clear = {}) {
  RandomStream rng(seed);
  return detail::make_tree(rng, 9.0, form, clear);
}

bool is_leaf(const ArticulatedMesh& m, size_t triangle) {
  const std::string& name = m.materials[m.material[triangle]].name;
  return name.rfind("foliage", 0) == 0 || name.rfind("needles", 0) == 0;
}

/// Share of the rays through a crown's side view (from -y, a 4 cm grid over its leaves'
/// bounds) that pass between a row's first and last leaf hit without meeting anything: the sky
/// seen through the crown, not round its outline.
double sky_through(const ArticulatedMesh& m) {
  Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (is_leaf(m, t)) {
      for (uint32_t v : m.triangles[t]) {
        const Vec3 p = m.vertices[v];
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
      }
    }
  }
  Scene scene;
  scene.add_static_mesh(detail::to_static_mesh(m, Rigid{}, "tree"));
  scene.commit();
  int inside = 0, open = 0;
  for (double z = lo.z; z <= hi.z; z += 0.04) {
    std::vector<bool> row;
    for (double x = lo.x; x <= hi.x; x += 0.04) {
      row.push_back(scene.intersect({x, lo.y - 5.0, z}, {0.0, 1.0, 0.0}, 50.0).has_value());
    }
    const auto first = std::find(row.begin(), row.end(), true);
    const auto last = std::find(row.rbegin(), row.rend(), true);
    if (first == row.end()) {
      continue;
    }
    for (auto it = first; it != last.base(); ++it) {
      ++inside;
      open += *it ? 0 : 1;
    }
  }
  return static_cast<double>(open) / std::max(inside, 1);
}

}  // namespace

TEST_CASE("a crown is clumps of leaves with sky between them, not one closed solid",
          "[sensors][world][trees]") {
  for (const TreeForm form : kForms) {
    for (uint64_t seed : {1, 2}) {
      const double sky = sky_through(tree(form, seed));
      INFO("form " << static_cast<int>(form) << " seed " << seed << ": sky " << sky);
      CHECK(sky > 0.01);  // gaps (a fastigiate crown is the densest)
      CHECK(sky < 0.6);   // still a crown
    }
  }
  RandomStream rng(5);
  const double bush = sky_through(detail::make_bush(rng, 1.5));
  INFO("bush: sky " << bush);
  CHECK(bush < 0.3);
}

TEST_CASE("plants shade smooth: unit vertex normals on the outer side of every face",
          "[sensors][world][trees]") {
  std::vector<ArticulatedMesh> plants;
  for (const TreeForm form : kForms) {
    plants.push_back(tree(form, 3));
  }
  RandomStream rng(4);
  plants.push_back(detail::make_bush(rng, 1.4));
  for (const ArticulatedMesh& m : plants) {
    REQUIRE(m.normals.size() == m.vertices.size());
    for (const Vec3& n : m.normals) {
      REQUIRE(std::fabs(norm(n) - 1.0) < 1e-9);  // every part is smooth
    }
    // Each face's normals lean its way (the mean of its three with its own normal, > 0), but
    // for a few faces in the folds of the lumpy clumps ...
    size_t against = 0;
    for (const auto& t : m.triangles) {
      const Vec3 face =
          cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
      against += dot(m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]], face) <= 0.0 ? 1 : 0;
    }
    INFO(against << " of " << m.triangles.size() << " faces against their normals");
    CHECK(against < m.triangles.size() / 100);
    // ... and faces face out: the trunk's normals point away from its axis near the ground, and
    // every clump (a closed part) encloses a positive volume.
    for (size_t v = 0; v < m.vertices.size() && &m != &plants.back(); ++v) {
      const Vec3 p = m.vertices[v];
      if (p.z > 0.05 && p.z < 0.3 && std::hypot(p.x, p.y) < 0.4) {
        CHECK(m.normals[v].x * p.x + m.normals[v].y * p.y > 0.0);
      }
    }
    std::vector<size_t> part(m.vertices.size());
    for (size_t v = 0; v < part.size(); ++v) {
      part[v] = v;
    }
    auto root = [&](size_t v) {
      while (part[v] != v) {
        v = part[v] = part[part[v]];
      }
      return v;
    };
    for (const auto& t : m.triangles) {
      part[root(t[1])] = root(t[0]);
      part[root(t[2])] = root(t[0]);
    }
    std::map<size_t, double> volume;
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    std::map<size_t, bool> closed;
    for (const auto& t : m.triangles) {
      volume[root(t[0])] += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]])) / 6.0;
      for (int k = 0; k < 3; ++k) {
        ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
      }
    }
    for (const auto& [edge, uses] : edges) {
      const size_t r = root(edge.first);
      closed.try_emplace(r, true);
      closed[r] = closed[r] && uses == 2;
    }
    size_t clumps = 0;
    for (const auto& [r, v] : volume) {
      if (closed[r]) {
        ++clumps;
        CHECK(v > 0.0);
      }
    }
    CHECK(clumps > 10);
  }
}

TEST_CASE("the same stream grows the same plant; forms, sizes and looks vary between streams",
          "[sensors][world][trees]") {
  for (const TreeForm form : kForms) {
    const ArticulatedMesh a = tree(form, 11);
    const ArticulatedMesh b = tree(form, 11);
    const ArticulatedMesh c = tree(form, 12);
    REQUIRE(a.vertices.size() == b.vertices.size());
    CHECK(std::equal(a.vertices.begin(), a.vertices.end(), b.vertices.begin(),
                     [](Vec3 p, Vec3 q) { return p.x == q.x && p.y == q.y && p.z == q.z; }));
    CHECK(a.triangles == b.triangles);
    CHECK(a.material == b.material);
    CHECK((a.vertices.size() != c.vertices.size() || a.vertices[40].x != c.vertices[40].x));
    for (const SemanticClass k : a.classes) {
      REQUIRE(k == SemanticClass::kVegetation);
    }
  }
  std::set<TreeForm> street, park;
  for (uint64_t seed = 0; seed < 200; ++seed) {
    RandomStream r1(seed), r2(seed);
    street.insert(detail::draw_tree_form(r1, false));
    park.insert(detail::draw_tree_form(r2, true));
  }
  CHECK(street.size() == 4);  // broadleaved only along sidewalks
  CHECK(!street.contains(TreeForm::kSpruce));
  CHECK(park.size() == 6);
}

TEST_CASE("a crown leaves a lamp head in it clear", "[sensors][world][trees]") {
  int reached = 0;
  for (const TreeForm form : kForms) {
    // A lamp head 1.8 m from the trunk at two thirds of the height: inside any crown.
    const detail::Clearance lamp{{1.8, 0.0, 6.0}, 1.5};
    auto leaf_vertices_near_lamp = [&](const ArticulatedMesh& m) {
      size_t n = 0;
      for (size_t t = 0; t < m.triangles.size(); ++t) {
        for (uint32_t v : m.triangles[t]) {
          n += is_leaf(m, t) && norm(m.vertices[v] - lamp.centre) < lamp.radius ? 1 : 0;
        }
      }
      return n;
    };
    const size_t within = leaf_vertices_near_lamp(tree(form, 21, std::span(&lamp, 1)));
    const size_t unpruned = leaf_vertices_near_lamp(tree(form, 21));
    INFO("form " << static_cast<int>(form) << ": leaf vertices round the lamp " << unpruned
                 << " unpruned");
    CHECK(within == 0);
    reached += unpruned > 0 ? 1 : 0;
  }
  CHECK(reached >= 3);  // the lamp stood in most crowns before they were pruned
}

TEST_CASE("the demo street's plants stay within a triangle budget", "[sensors][world][trees]") {
  const auto map = corsa::test::load_map(std::filesystem::path(CORSA_SOURCE_DIR) /
                                         "scenarios/demo/city_street.xodr");
  WorldOptions with;
  with.seed = 3;
  WorldOptions without = with;
  without.vegetation = false;
  const auto a = corsa::test::build_world_scene(map, with);
  const auto b = corsa::test::build_world_scene(map, without);
  const size_t plants = a->report.trees + a->report.bushes;
  const size_t triangles = a->scene.static_triangle_count() - b->scene.static_triangle_count();
  INFO(a->report.trees << " trees, " << a->report.bushes << " bushes: " << triangles
                       << " triangles");
  REQUIRE(plants > 20);
  // Some 12,000 triangles a plant (a bush a few hundred): the BVH of a street of them fits
  // in tens of megabytes.
  CHECK(triangles / plants < 16000);
}
