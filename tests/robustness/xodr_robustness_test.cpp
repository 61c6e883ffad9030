// Broken OpenDRIVE maps through `corsa validate`, `corsa map info` and `corsa map mesh`: every
// case ends with exit 0 (still valid) or exit 2 and a located error, within the time limit, and a
// rejected mesh leaves no file behind.

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bounded_run.h"
#include "mutations.h"

namespace corsa::test {
namespace {

std::string shared_map(const std::string& name) {
  return slurp(std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr" / name);
}

/// The maps of tests/robustness/corpus that must load (ok_*.xodr), in name order.
std::vector<std::filesystem::path> valid_corpus_maps() {
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  std::vector<std::filesystem::path> maps;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    if (entry.path().extension() == ".xodr" &&
        entry.path().filename().string().starts_with("ok_")) {
      maps.push_back(entry.path());
    }
  }
  std::sort(maps.begin(), maps.end());
  return maps;
}

/// Writes `text` as map.xodr in `dir`, runs `corsa map mesh` on it into dir/out.obj and checks
/// the outcome; a rejected map must leave only map.xodr in the folder.
void check_mesh_case(const std::string& name, const std::string& text) {
  TempDir dir;
  const auto map = dir.path() / "map.xodr";
  std::ofstream(map, std::ios::binary) << text;
  const BoundedResult result =
      run_bounded({"map", "mesh", map.string(), "-o", (dir.path() / "out.obj").string()});
  check_rejected_or_ok(name, result, true);
  if (result.exit_code != 0) {
    INFO(describe(name, result));
    CHECK(entry_names(dir.path()) == std::set<std::string>{"map.xodr"});
  }
}

void check_info_case(const std::string& name, const std::string& text, bool may_succeed) {
  TempDir dir;
  const auto map = dir.path() / "map.xodr";
  std::ofstream(map, std::ios::binary) << text;
  check_rejected_or_ok(name, run_bounded({"map", "info", map.string()}), may_succeed);
}

TEST_CASE("Truncated OpenDRIVE maps are rejected with a located error and no mesh file",
          "[robustness][xodr]") {
  for (const char* file : {"straight_500m.xodr", "Ex_Line-Spiral-Arc.xodr", "fabriksgatan.xodr"}) {
    for (const Mutant& mutant :
         truncations(shared_map(file), {0.0, 0.002, 0.05, 0.31, 0.5, 0.77, 0.995})) {
      check_mesh_case(std::string(file) + " " + mutant.name, mutant.text);
    }
  }
}

TEST_CASE("OpenDRIVE maps with random bytes overwritten never crash, hang or half-write",
          "[robustness][xodr]") {
  uint32_t seed = 1;
  for (const char* file : {"straight_500m.xodr", "Ex_Line-Spiral-Arc.xodr", "fabriksgatan.xodr"}) {
    for (const Mutant& mutant : byte_flips(shared_map(file), seed++, 12)) {
      check_mesh_case(std::string(file) + " " + mutant.name, mutant.text);
    }
  }
}

TEST_CASE("NaN, infinite, text, negative and huge numbers in OpenDRIVE attributes are handled",
          "[robustness][xodr]") {
  struct Target {
    const char* file;
    const char* element;
    const char* attribute;
  };
  const Target targets[] = {
      {"straight_500m.xodr", "road", "length"},
      {"straight_500m.xodr", "geometry", "length"},
      {"straight_500m.xodr", "geometry", "x"},
      {"straight_500m.xodr", "geometry", "hdg"},
      {"straight_500m.xodr", "width", "a"},
      {"straight_500m.xodr", "width", "d"},
      {"straight_500m.xodr", "laneSection", "s"},
      {"straight_500m.xodr", "lane", "id"},
      {"straight_500m.xodr", "elevation", "b"},
      {"Ex_Line-Spiral-Arc.xodr", "spiral", "curvStart"},
      {"Ex_Line-Spiral-Arc.xodr", "arc", "curvature"},
  };
  for (const Target& target : targets) {
    const std::string original = shared_map(target.file);
    for (const std::string& value : bad_numbers()) {
      const std::string text = with_attribute(original, target.element, target.attribute, value);
      REQUIRE_FALSE(text.empty());
      check_info_case(std::string(target.file) + " <" + target.element + " " + target.attribute +
                          "=\"" + value + "\">",
                      text, true);
    }
  }
}

TEST_CASE("OpenDRIVE elements without a required attribute are rejected at their line",
          "[robustness][xodr]") {
  struct Target {
    const char* element;
    const char* attribute;
  };
  const Target targets[] = {{"road", "id"},       {"road", "length"},  {"geometry", "s"},
                            {"geometry", "x"},    {"geometry", "hdg"}, {"geometry", "length"},
                            {"laneSection", "s"}, {"lane", "id"},      {"width", "a"},
                            {"width", "sOffset"}};
  const std::string original = shared_map("straight_500m.xodr");
  for (const Target& target : targets) {
    const std::string text = without_attribute(original, target.element, target.attribute);
    REQUIRE_FALSE(text.empty());
    check_info_case(std::string("<") + target.element + "> without " + target.attribute, text,
                    false);
  }
}

TEST_CASE("Hand-made OpenDRIVE files of the corpus load, or are rejected at their line",
          "[robustness][xodr]") {
  // corpus/bad_*.xodr must be rejected (exit 2, located in that file); corpus/ok_*.xodr are valid
  // maps that once crashed or hung Corsa and must now load (exit 0) in time. Each file's comment
  // says what it checks.
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  size_t bad = 0;
  size_t ok = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".xodr") {
      continue;
    }
    const bool must_fail = name.starts_with("bad_");
    REQUIRE((must_fail || name.starts_with("ok_")));
    ++(must_fail ? bad : ok);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"validate", entry.path().string()},
          std::vector<std::string>{"map", "info", entry.path().string()}}) {
      const BoundedResult result = run_bounded(args);
      INFO(describe(args[0] + " " + name, result));
      CHECK_FALSE(result.timed_out);
      if (must_fail) {
        CHECK(result.exit_code == 2);
        CHECK(has_located_error(result.err));
        CHECK(result.err.find(name + ":") != std::string::npos);
      } else {
        CHECK(result.exit_code == 0);
      }
    }
  }
  CHECK(bad >= 10);
  CHECK(ok >= 2);
}

/// The OBJ `v` lines of `obj` that do not hold exactly three numbers.
std::vector<std::string> bad_vertex_lines(const std::string& obj) {
  std::vector<std::string> bad;
  std::istringstream lines(obj);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("v ")) {
      continue;
    }
    std::istringstream fields(line.substr(2));
    double value = 0.0;
    int count = 0;
    while (fields >> value) {
      ++count;
    }
    if (count != 3 || !fields.eof()) {
      bad.push_back(line.substr(0, 80));
    }
  }
  return bad;
}

TEST_CASE("The valid maps of the corpus mesh in time, every OBJ vertex with three coordinates",
          "[robustness][xodr]") {
  // ok_spiral_overlapping_line.xodr ran for minutes; ok_lane_width_1e206.xodr lost coordinates.
  for (const std::filesystem::path& map : valid_corpus_maps()) {
    const std::string name = map.filename().string();
    TempDir out;
    const auto obj = out.path() / "map.obj";
    const BoundedResult result = run_bounded({"map", "mesh", map.string(), "-o", obj.string()});
    INFO(describe("map mesh " + name, result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 0);
    if (result.exit_code == 0) {
      CHECK(bad_vertex_lines(slurp(obj)).empty());
    }
  }
}

TEST_CASE("map holes and map render end in time on every valid map of the corpus",
          "[robustness][xodr]") {
  // Found by tests/robustness/campaign.py: `map holes` on ok_lane_width_1e20.xodr and
  // ok_lane_width_1e206.xodr never ended (each lane triangle was sorted into every 16 m bin it
  // covers: 1e36 of them).
  for (const std::filesystem::path& map : valid_corpus_maps()) {
    const std::string name = map.filename().string();
    TempDir out;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"map", "holes", map.string(), "--list"},
          std::vector<std::string>{"map", "render", map.string(), "-o",
                                   (out.path() / "map.png").string(), "--size", "128"}}) {
      const BoundedResult result = run_bounded(args);
      INFO(describe(args[1] + " " + name, result));
      CHECK_FALSE(result.timed_out);
      CHECK(result.exit_code == 0);
      CHECK(result.cpu_seconds < 10);  // CPU time: wall time depends on the load
    }
  }
}

TEST_CASE("A road surface beyond the range of doubles is refused at its road, with no mesh",
          "[robustness][xodr]") {
  // Two lanes 1.7e308 m wide: their outer border is infinite.
  const std::string lane =
      "<lane id=\"ID\" type=\"driving\"><width sOffset=\"0\" a=\"1.7e308\" b=\"0\" c=\"0\" "
      "d=\"0\"/></lane>\n";
  std::string lanes;
  for (const char* id : {"-2", "-1"}) {
    std::string text = lane;
    lanes += text.replace(text.find("ID"), 2, id);
  }
  std::string map = slurp(std::filesystem::path(CORSA_SOURCE_DIR) /
                          "tests/robustness/corpus/ok_minimal_road.xodr");
  const size_t right = map.find("<right>") + 7;
  const size_t end = map.find("</right>");
  map.replace(right, end - right, "\n" + lanes);
  for (const char* extension : {".obj", ".ply"}) {
    TempDir dir;
    std::ofstream(dir.path() / "map.xodr") << map;
    const BoundedResult result =
        run_bounded({"map", "mesh", (dir.path() / "map.xodr").string(), "-o",
                     (dir.path() / (std::string("m") + extension)).string()});
    INFO(describe(std::string("two lanes of 1.7e308 m to ") + extension, result));
    CHECK(result.exit_code == 2);
    CHECK(result.err.find("map.xodr:5: error: road '1': its surface reaches beyond the range of "
                          "numbers") != std::string::npos);
    CHECK(entry_names(dir.path()) == std::set<std::string>{"map.xodr"});
  }
}

}  // namespace
}  // namespace corsa::test

namespace corsa::test {
namespace {

TEST_CASE("OpenDRIVE maps that break the standard with a clear meaning warn at their line",
          "[robustness][xodr]") {
  // Each loaded without a word before: a lane section beyond its road's end, a negative lane
  // width, a zero-length road, a road linked to itself.
  struct Case {
    const char* file;
    std::vector<std::string> warnings;
  };
  const Case cases[] = {
      {"ok_lane_section_beyond_road_end.xodr",
       {":23: warning: road '1': laneSection at s=150 starts beyond the road's end (length 100 "
        "m); it covers nothing"}},
      {"ok_negative_lane_width.xodr",
       {":18: warning: road '1': lane -1 has a negative width (-1.5 m in its width record at "
        "sOffset 0); taken as 0 m where it is negative"}},
      {"ok_zero_length_road.xodr",
       {":5: warning: road '1' has length 0, which OpenDRIVE does not allow"}},
      {"ok_road_linked_to_itself.xodr",
       {":5: warning: road '1' is its own successor at its end; a road cannot continue into the "
        "same end",
        ":5: warning: road '1' is its own predecessor, closing a loop, but its end is 100.000 m "
        "from its start"}},
  };
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  for (const Case& c : cases) {
    const BoundedResult result = run_bounded({"map", "info", (corpus / c.file).string()});
    INFO(describe(std::string("map info ") + c.file, result));
    CHECK(result.exit_code == 0);
    for (const std::string& warning : c.warnings) {
      CHECK(result.err.find(c.file + warning) != std::string::npos);
    }
  }
}

}  // namespace
}  // namespace corsa::test
