// Inputs that are not regular files, or are too large: a FIFO without a writer (every reader
// blocked on it for ever), a character device (/dev/zero was read until memory ran out) and a
// sparse file past the size cap. Each reader refuses them at once with exit 2 and a message
// naming the path and saying why.

#include <sys/stat.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "bounded_run.h"

namespace corsa::test {
namespace {

namespace fs = std::filesystem;

/// Seconds a refusal may take: it happens before any reading.
constexpr int kLimit = 10;

void make_fifo(const fs::path& path) { REQUIRE(::mkfifo(path.c_str(), 0600) == 0); }

/// Runs `args` and checks exit 2, in time, with `path: error: ...` holding `why`.
void check_refused(const std::vector<std::string>& args, const std::string& path,
                   const std::string& why) {
  const BoundedResult result = run_bounded(args, kLimit);
  INFO(describe(joined(args), result));
  CHECK_FALSE(result.timed_out);
  CHECK(result.exit_code == 2);
  CHECK(result.err.find(path + ": error: ") != std::string::npos);
  CHECK(result.err.find(why) != std::string::npos);
}

TEST_CASE("Every reader refuses a FIFO at once instead of waiting for a writer",
          "[robustness][paths]") {
  TempDir dir;
  const auto in = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::string why = "is a FIFO (named pipe); Corsa reads its inputs from regular files only";
  for (const char* name : {"map.xodr", "scenario.xosc", "rig.xml", "queries.csv"}) {
    make_fifo(dir.path() / name);
  }
  check_refused({"validate", in("scenario.xosc")}, in("scenario.xosc"), why);
  check_refused({"validate", in("map.xodr")}, in("map.xodr"), why);
  check_refused({"map", "info", in("map.xodr")}, in("map.xodr"), why);
  check_refused({"map", "mesh", in("map.xodr"), "-o", in("out/m.obj")}, in("map.xodr"), why);
  check_refused({"map", "query", kMap, "--in", in("queries.csv")}, in("queries.csv"), why);
  check_refused({"run", in("scenario.xosc"), "--quiet"}, in("scenario.xosc"), why);
  check_refused({"sweep", in("scenario.xosc"), "--param", "a=1:2:1", "-o", in("out/s"), "--quiet"},
                in("scenario.xosc"), why);
  check_refused({"run", kScenario, "--quiet", "--rig", in("rig.xml"), "-o", in("out/d")},
                in("rig.xml"), why);
  // A scenario naming a FIFO as its map: refused at the LogicFile's line.
  std::string scenario = cut_in_text();
  const size_t at = scenario.find("filepath=\"") + 10;
  scenario.replace(at, scenario.find('"', at) - at, in("map.xodr"));
  std::ofstream(dir.path() / "named.xosc") << scenario;
  for (const char* command : {"validate", "run"}) {
    const BoundedResult result = run_bounded({command, in("named.xosc")}, kLimit);
    INFO(describe(std::string(command) + " of a scenario whose map is a FIFO", result));
    CHECK(result.exit_code == 2);
    CHECK(has_located_error(result.err));
    CHECK(result.err.find(in("map.xodr")) != std::string::npos);
  }
  // A suite folder whose manifest is a FIFO.
  fs::create_directory(dir.path() / "suite");
  make_fifo(dir.path() / "suite" / "suite.xml");
  check_refused({"test", in("suite"), "--quiet"}, in("suite/suite.xml"), why);
  CHECK_FALSE(fs::exists(dir.path() / "out"));
}

TEST_CASE("NGII layers that are FIFOs are refused by name", "[robustness][ngii]") {
  const fs::path kcity = fs::path(CORSA_SHARED_DIR) / "data" / "ngii" / "kcity";
  for (const char* file : {"A2_LINK.shp", "A2_LINK.shx", "A2_LINK.dbf", "A2_LINK.prj"}) {
    TempDir dir;
    const fs::path layers = dir.path() / "kcity";
    fs::copy(kcity, layers);
    fs::remove(layers / file);
    make_fifo(layers / file);
    check_refused({"convert", "ngii", layers.string(), "-o", (dir.path() / "k.xodr").string()},
                  (layers / file).string(), "is a FIFO");
    CHECK_FALSE(fs::exists(dir.path() / "k.xodr"));
  }
}

TEST_CASE("A character device is refused instead of read until memory runs out",
          "[robustness][paths]") {
  TempDir out;
  const std::string why = "is a character device; Corsa reads its inputs from regular files only";
  check_refused({"validate", "/dev/zero"}, "/dev/zero", why);
  check_refused({"map", "info", "/dev/zero"}, "/dev/zero", why);
  check_refused({"run", "/dev/zero", "--quiet"}, "/dev/zero", why);
  check_refused({"map", "query", kMap, "--in", "/dev/zero"}, "/dev/zero", why);
  check_refused(
      {"run", kScenario, "--quiet", "--rig", "/dev/zero", "-o", (out.path() / "d").string()},
      "/dev/zero", why);
  CHECK(out.entries() == 0);
}

TEST_CASE("An input file past the 512 MiB cap is refused before it is read",
          "[robustness][paths]") {
  TempDir dir;
  // Sparse: takes no disk space, and reads as NUL bytes.
  for (const char* name : {"big.xodr", "big.xosc"}) {
    const fs::path big = dir.path() / name;
    std::ofstream(big).close();
    fs::resize_file(big, (uint64_t{512} << 20) + 1);
  }
  const std::string why = "is 536870913 bytes, more than the 512 MiB Corsa reads from one input";
  check_refused({"map", "info", (dir.path() / "big.xodr").string()},
                (dir.path() / "big.xodr").string(), why);
  check_refused({"validate", (dir.path() / "big.xosc").string()},
                (dir.path() / "big.xosc").string(), why);
}

TEST_CASE("map query reads standard input in bounded lines", "[robustness][paths]") {
  // 5,000 bytes without a line break: refused at line 1, not held whole.
  const ProcessResult result = run_corsa({"map", "query", kMap}, std::string(5000, '1'));
  CHECK(result.exit_code == 2);
  CHECK(result.err.find("<stdin>:1: error: line longer than 4096 bytes") != std::string::npos);
}

}  // namespace
}  // namespace corsa::test
