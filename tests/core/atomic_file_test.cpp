#include "corsa/core/atomic_file.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "corsa/core/diagnostic.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

TEST_CASE("an atomic file appears only when committed", "[core][atomic_file]") {
  corsa::test::TempDir dir;
  const fs::path target = dir.path() / "out.csv";
  {
    corsa::AtomicFile file(target);
    file.stream() << "a,b\n1,2\n";
    CHECK_FALSE(fs::exists(target));
    CHECK(fs::exists(file.temporary()));
    file.commit();
  }
  CHECK(corsa::read_file(target) == "a,b\n1,2\n");
  CHECK(dir.entries() == 1);
}

TEST_CASE("an uncommitted atomic file leaves no trace and keeps the old file",
          "[core][atomic_file]") {
  corsa::test::TempDir dir;
  const fs::path target = dir.path() / "out.csv";
  corsa::write_file_atomic(target, "old");
  try {
    corsa::AtomicFile file(target);
    file.stream() << "half-written";
    throw std::runtime_error("interrupted");
  } catch (const std::runtime_error&) {
  }
  CHECK(corsa::read_file(target) == "old");
  CHECK(dir.entries() == 1);
}

TEST_CASE("an atomic file creates missing folders and removes them when not committed",
          "[core][atomic_file]") {
  corsa::test::TempDir dir;
  const fs::path target = dir.path() / "no" / "such" / "dir" / "out.csv";
  {
    corsa::AtomicFile file(target);
    file.stream() << "abandoned";
    CHECK(fs::is_directory(target.parent_path()));
  }
  CHECK(dir.entries() == 0);
  corsa::write_file_atomic(target, "kept");
  CHECK(corsa::read_file(target) == "kept");
}

TEST_CASE("an atomic file onto a folder or through a file fails with the path named",
          "[core][atomic_file]") {
  corsa::test::TempDir dir;
  corsa::write_file_atomic(dir.path() / "plain.txt", "a file");
  for (const fs::path& target : {dir.path(), dir.path() / "plain.txt" / "deeper" / "out.csv"}) {
    try {
      corsa::AtomicFile file(target);
      FAIL("expected an error");
    } catch (const corsa::InputError& error) {
      CHECK(error.diagnostic().file == target.string());
      CHECK_THAT(error.what(), Catch::Contains("folder"));
    }
    CHECK_THROWS_AS(corsa::check_output_file(target), corsa::InputError);
  }
  CHECK_THROWS_AS(corsa::check_output_folder(dir.path() / "plain.txt"), corsa::InputError);
  CHECK_NOTHROW(corsa::check_output_folder(dir.path() / "new" / "folder"));
  CHECK(dir.entries() == 1);
}

TEST_CASE("reading a missing file names it", "[core][atomic_file]") {
  CHECK_THROWS_WITH(corsa::read_file("/no/such/file.xodr"),
                    Catch::StartsWith("/no/such/file.xodr: error: cannot open file"));
}

TEST_CASE("an atomic file's temporary is a new regular file, never a link planted before",
          "[core][atomic_file]") {
  corsa::test::TempDir dir;
  corsa::AtomicFile file(dir.path() / "out.csv");
  CHECK(fs::is_regular_file(fs::symlink_status(file.temporary())));
  file.stream() << "x";
  file.commit();
  CHECK(corsa::read_file(dir.path() / "out.csv") == "x");
}

TEST_CASE("stale temporaries are removed, live ones and other files are kept",
          "[core][atomic_file]") {
  corsa::test::TempDir dir;
  // As a killed process leaves them: no lock held.
  std::ofstream(dir.path() / ".trajectories.csv.tmp.4242.0") << "half";
  fs::create_directories(dir.path() / "variants" / "7");
  std::ofstream(dir.path() / "variants" / "7" / ".result.csv.tmp.17.3") << "half";
  fs::create_directories(dir.path() / "a" / "b" / "c");
  std::ofstream(dir.path() / "a" / "b" / "c" / ".deep.tmp.1.1") << "too deep";
  // Not Corsa's temporaries, or not stale.
  std::ofstream(dir.path() / ".notes.tmp") << "user file";
  std::ofstream(dir.path() / "x.tmp.1.2") << "no leading dot";
  std::ofstream(dir.path() / "target") << "kept";
  fs::create_symlink(dir.path() / "target", dir.path() / ".link.tmp.5.5");
  corsa::AtomicFile live(dir.path() / "live.csv");
  live.stream() << "being written";

  CHECK(corsa::remove_stale_temporaries(dir.path()) == 1);
  CHECK_FALSE(fs::exists(dir.path() / ".trajectories.csv.tmp.4242.0"));
  CHECK(fs::exists(dir.path() / "variants" / "7" / ".result.csv.tmp.17.3"));
  CHECK(corsa::remove_stale_temporaries(dir.path(), 2) == 1);
  CHECK_FALSE(fs::exists(dir.path() / "variants" / "7" / ".result.csv.tmp.17.3"));
  CHECK(fs::exists(dir.path() / "a" / "b" / "c" / ".deep.tmp.1.1"));
  CHECK(fs::exists(live.temporary()));
  CHECK(fs::exists(dir.path() / ".notes.tmp"));
  CHECK(fs::exists(dir.path() / "x.tmp.1.2"));
  CHECK(fs::is_symlink(dir.path() / ".link.tmp.5.5"));
  CHECK(corsa::read_file(dir.path() / "target") == "kept");
  live.commit();
  CHECK(corsa::read_file(dir.path() / "live.csv") == "being written");
}
