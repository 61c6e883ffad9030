// `corsa test --update-goldens` writes golden files inside the suite folder only: a manifest's
// `<Golden file="../outside/x.csv">`, an absolute path or a linked folder inside the suite is
// refused at its line before any test runs, with nothing written, unless the user passes
// --goldens-outside.

#include <fstream>
#include <string>
#include <vector>

#include "bounded_run.h"

namespace corsa::test {
namespace {

namespace fs = std::filesystem;

/// A suite of one-second cut-in tests, one per golden attribute given ("" for the default
/// goldens/<test>.csv), in dir/suite.
void write_suite(const TempDir& dir, const std::vector<std::string>& goldens) {
  fs::create_directories(dir.path() / "suite");
  std::ofstream(dir.path() / "suite" / "cut_in.xosc") << cut_in_text();
  std::ofstream manifest(dir.path() / "suite" / "suite.xml");
  manifest << "<?xml version=\"1.0\"?>\n"
           << "<Suite version=\"1\" name=\"goldens\" duration=\"1\">\n";  // line 2
  for (size_t i = 0; i < goldens.size(); ++i) {
    manifest << "  <Test name=\"t" << i << "\" scenario=\"cut_in.xosc\">\n"  // line 3 + 3i
             << "    <Golden" << (goldens[i].empty() ? "" : " file=\"" + goldens[i] + "\"")
             << " every=\"10\"/>\n"  // line 4 + 3i
             << "  </Test>\n";
  }
  manifest << "</Suite>\n";
}

std::vector<std::string> update(const TempDir& dir) {
  return {"test", (dir.path() / "suite").string(), "--update-goldens", "--quiet", "-j", "1"};
}

TEST_CASE("--update-goldens refuses goldens outside the suite folder, all at their lines",
          "[robustness][suite][output]") {
  TempDir dir;
  fs::create_directories(dir.path() / "outside");
  std::ofstream(dir.path() / "outside" / "x.csv") << "the user's own file\n";
  const std::string absolute = (dir.path() / "absolute.csv").string();
  write_suite(dir, {"", "../outside/x.csv", absolute});
  const BoundedResult refused = run_bounded(update(dir));
  INFO(describe("update-goldens with goldens outside", refused));
  CHECK(refused.exit_code == 2);
  const std::string manifest = (dir.path() / "suite" / "suite.xml").string();
  CHECK(refused.err.find(
            manifest + ":7: error: golden file " + (dir.path() / "outside" / "x.csv").string() +
            " of test 't1' is outside the suite folder; --update-goldens writes "
            "only inside it (pass --goldens-outside to write there)") != std::string::npos);
  CHECK(refused.err.find(manifest + ":10: error: golden file " + absolute +
                         " of test 't2' is outside the suite folder") != std::string::npos);
  // Nothing written anywhere, not even the golden inside.
  CHECK(slurp(dir.path() / "outside" / "x.csv") == "the user's own file\n");
  CHECK(entry_names(dir.path()) == std::set<std::string>{"outside", "suite"});
  CHECK(entry_names(dir.path() / "suite") == std::set<std::string>{"cut_in.xosc", "suite.xml"});

  std::vector<std::string> allowed = update(dir);
  allowed.push_back("--goldens-outside");
  const BoundedResult written = run_bounded(allowed);
  INFO(describe("update-goldens --goldens-outside", written));
  CHECK(written.exit_code == 0);
  CHECK(slurp(dir.path() / "outside" / "x.csv").starts_with("time,entity,"));
  CHECK(slurp(absolute).starts_with("time,entity,"));
  CHECK(slurp(dir.path() / "suite" / "goldens" / "t0.csv").starts_with("time,entity,"));
}

TEST_CASE("--update-goldens never writes through a linked folder inside the suite",
          "[robustness][suite][output]") {
  TempDir dir;
  fs::create_directories(dir.path() / "elsewhere");
  write_suite(dir, {""});
  fs::create_directory_symlink(dir.path() / "elsewhere", dir.path() / "suite" / "goldens");
  const BoundedResult refused = run_bounded(update(dir));
  INFO(describe("update-goldens through a linked goldens folder", refused));
  CHECK(refused.exit_code == 2);
  CHECK(refused.err.find((dir.path() / "suite" / "suite.xml").string() + ":4: error: golden file " +
                         (dir.path() / "suite" / "goldens" / "t0.csv").string() +
                         " of test 't0' lies in " + (dir.path() / "suite" / "goldens").string() +
                         ", a symbolic link") != std::string::npos);
  CHECK(fs::is_empty(dir.path() / "elsewhere"));
}

}  // namespace
}  // namespace corsa::test
