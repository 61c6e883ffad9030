#include "corsa/core/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

TEST_CASE("an output folder has one writer at a time", "[core][output_lock]") {
  corsa::test::TempDir dir;
  const fs::path lock_file = dir.path() / ".corsa.lock";
  {
    const corsa::OutputLock lock(dir.path());
    CHECK(fs::is_regular_file(lock_file));
    CHECK(
        corsa::read_file(lock_file).starts_with("pid " + std::to_string(::getpid()) + " on host "));
    try {
      const corsa::OutputLock second(dir.path());
      FAIL("a second writer was let in");
    } catch (const corsa::InputError& error) {
      CHECK(error.diagnostic().file == dir.path().string());
      CHECK_THAT(error.what(), Catch::Contains("another corsa (pid " + std::to_string(::getpid())));
      CHECK_THAT(error.what(), Catch::Contains("is writing into this folder"));
    }
    CHECK(fs::is_regular_file(lock_file));
  }
  CHECK(dir.entries() == 0);  // released, and no staging file left
  std::optional<corsa::OutputLock> again;
  CHECK_NOTHROW(again.emplace(dir.path()));
}

TEST_CASE("the stale lock of a killed writer is taken over", "[core][output_lock]") {
  corsa::test::TempDir dir;
  // As a killed process leaves it: the file, with nobody holding its flock.
  std::ofstream(dir.path() / ".corsa.lock") << "pid 999999 on host elsewhere\n";
  std::ofstream(dir.path() / ".corsa.lock.tmp.999999.0") << "";
  {
    const corsa::OutputLock lock(dir.path());
    CHECK(corsa::read_file(dir.path() / ".corsa.lock")
              .starts_with("pid " + std::to_string(::getpid())));
  }
  corsa::remove_stale_temporaries(dir.path());
  CHECK(dir.entries() == 0);
}

TEST_CASE("a stale lock another writer is removing is taken over, not reported as held",
          "[core][output_lock][race]") {
  corsa::test::TempDir dir;
  const fs::path lock_file = dir.path() / ".corsa.lock";
  std::ofstream(lock_file) << "pid 999999 on host elsewhere\n";
  // Another writer judging the same stale lock: it holds the flock for a moment, then removes it.
  const int judge = ::open(lock_file.c_str(), O_RDONLY | O_CLOEXEC);
  REQUIRE(judge >= 0);
  REQUIRE(::flock(judge, LOCK_EX | LOCK_NB) == 0);
  std::thread other([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::unlink(lock_file.c_str());
    ::close(judge);
  });
  std::optional<corsa::OutputLock> lock;
  CHECK_NOTHROW(lock.emplace(dir.path()));
  other.join();
  CHECK(corsa::read_file(lock_file).starts_with("pid " + std::to_string(::getpid())));
}

TEST_CASE("a folder that cannot hold the lock is an error naming it", "[core][output_lock]") {
  corsa::test::TempDir dir;
  CHECK_THROWS_WITH(corsa::OutputLock(dir.path() / "missing"),
                    Catch::StartsWith((dir.path() / "missing").string() +
                                      ": error: cannot lock the output folder"));
}
