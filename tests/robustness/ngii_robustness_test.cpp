// Broken NGII layers through `corsa convert ngii`: a layer file that is present but cannot be
// read (optional layers B2 and C1 included) and a .prj whose WKT PROJ cannot understand end with
// exit 2 and a message naming the file, and no OpenDRIVE file is written. The K-City layers from
// ../shared are copied and broken on the fly; every case fails while reading, before conversion.

#include <random>
#include <string>
#include <vector>

#include "bounded_run.h"

namespace corsa::test {
namespace {

namespace fs = std::filesystem;

const fs::path kKCity = fs::path(CORSA_SHARED_DIR) / "data" / "ngii" / "kcity";

/// `size` bytes from a fixed seed.
std::string garbage(size_t size, uint32_t seed) {
  std::mt19937 engine(seed);
  std::string bytes(size, '\0');
  for (char& c : bytes) {
    c = static_cast<char>(engine() % 256);
  }
  return bytes;
}

/// A copy of K-City's layers in `dir`/kcity with `file` replaced by `content`.
fs::path broken_copy(const TempDir& dir, const std::string& file, const std::string& content) {
  const fs::path layers = dir.path() / "kcity";
  fs::copy(kKCity, layers);
  std::ofstream(layers / file, std::ios::binary | std::ios::trunc) << content;
  return layers;
}

/// Runs the conversion and checks exit 2, a message about `file` and no output.
BoundedResult check_conversion_rejected(const std::string& name, const TempDir& dir,
                                        const fs::path& layers, const std::string& file) {
  const fs::path out = dir.path() / "out";
  fs::create_directory(out);
  const BoundedResult result =
      run_bounded({"convert", "ngii", layers.string(), "-o", (out / "map.xodr").string(),
                   "--report", (out / "fixes.csv").string(), "--quiet"});
  INFO(describe(name, result));
  CHECK_FALSE(result.timed_out);
  CHECK(result.exit_code == 2);
  // `file: record N: error:` for a bad record, `file: error:` for a file that cannot be opened.
  CHECK((has_located_error(result.err) || has_file_error(result.err, (layers / file).string())));
  CHECK(result.err.find(file) != std::string::npos);
  CHECK(fs::is_empty(out));
  return result;
}

TEST_CASE("A present but unreadable optional NGII layer is an error, not a warning",
          "[robustness][ngii]") {
  for (const std::string layer : {"C1_TRAFFICLIGHT", "B2_SURFACELINEMARK"}) {
    const std::string shp = layer + ".shp";
    const auto original = static_cast<size_t>(fs::file_size(kKCity / shp));
    const std::string text = slurp(kKCity / shp);
    struct Case {
      std::string what;
      std::string file;
      std::string content;
      std::string named;  ///< the file the message names ("" = `file`)
    };
    const std::vector<Case> cases = {
        // The header (first 100 bytes) kept: shapelib opens it and reads garbage records.
        {"records overwritten", shp, text.substr(0, 100) + garbage(original - 100, 3), ""},
        {"all garbage", shp, garbage(original, 5), ""},
        {"truncated", shp, text.substr(0, original / 2), ""},
        // shapelib cannot tell which of the two headers is bad: the .shp is named.
        {"index garbage", layer + ".shx", garbage(4096, 7), shp},
        {"table garbage", layer + ".dbf", garbage(4096, 9), ""},
        {"empty table", layer + ".dbf", "", ""},
    };
    for (const Case& c : cases) {
      // B2 is read by the same code as C1: two of its cases are enough (the binary stays fast).
      if (layer == "B2_SURFACELINEMARK" && c.what != "records overwritten" &&
          c.what != "table garbage") {
        continue;
      }
      TempDir dir;
      const fs::path layers = broken_copy(dir, c.file, c.content);
      check_conversion_rejected(c.file + " " + c.what, dir, layers,
                                c.named.empty() ? c.file : c.named);
    }
  }
}

TEST_CASE("A .prj that PROJ cannot understand is named with PROJ's reason in words",
          "[robustness][ngii]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"random bytes", garbage(300, 11)},
      {"plain text", "hello world\n"},
      {"truncated WKT", "PROJCS[\"Korea 2000 / Central Belt 2010\",GEOGCS[\"Korea 2000\","},
      {"unknown keyword", "NOTAWKT[\"x\"]"},
  };
  for (const auto& [what, content] : cases) {
    TempDir dir;
    const fs::path layers = broken_copy(dir, "A2_LINK.prj", content);
    const BoundedResult result =
        check_conversion_rejected("A2_LINK.prj " + what, dir, layers, "A2_LINK.prj");
    INFO(what << ": " << result.err);
    CHECK(result.err.find("could not be understood; PROJ says: ") != std::string::npos);
    CHECK(result.err.find("Unknown error") == std::string::npos);
    CHECK(result.err.find("code 4096") == std::string::npos);
  }
}

TEST_CASE("A vertex outside its record's bounding box is a damaged record, refused at once",
          "[robustness][ngii]") {
  // Found by tests/robustness/campaign.py: one byte of K-City's A2_LINK.shp changed (record 175,
  // vertex 108, y 4124484 -> 6.1e290). The coordinate is finite, so the record was read, and the
  // road fit then evaluated clothoids along a 1e290 m line until the time limit.
  const std::string shp = slurp(kKCity / "A2_LINK.shp");
  constexpr size_t kByte = 423771;  // the highest byte of that y but one
  REQUIRE(shp.size() > kByte);
  REQUIRE(static_cast<unsigned char>(shp[kByte]) == 0x41);
  std::string broken = shp;
  broken[kByte] = static_cast<char>(0x7c);
  TempDir dir;
  const fs::path layers = broken_copy(dir, "A2_LINK.shp", broken);
  const BoundedResult result =
      check_conversion_rejected("A2_LINK.shp vertex 6e290", dir, layers, "A2_LINK.shp");
  INFO(result.err);
  CHECK(result.cpu_seconds < 10);  // CPU time: wall time depends on the load
  CHECK(result.err.find("A2_LINK.shp: record 174: error: corrupt shape record: vertex 108 "
                        "(302269.305, 6.133177876e+290, 28.31200027) lies outside the record's "
                        "bounding box") != std::string::npos);
}

}  // namespace
}  // namespace corsa::test
