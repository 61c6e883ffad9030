// Writers and the cleanup of killed writers' temporaries running at once in one folder, as two
// `corsa run` writing into one output folder do: the cleanup must never take a live writer's
// temporary for a stale one, whatever point of its creation the writer has reached.

#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/locked_temporary.h"
#include "corsa/core/output_lock.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

/// Runs `write` `rounds` times on one thread while another removes stale temporaries from
/// `folder` without pause; returns how many temporaries the cleanup removed.
template <typename Write>
size_t removed_beside_writer(const fs::path& folder, int rounds, Write write) {
  std::atomic<bool> done{false};
  size_t removed = 0;
  std::thread cleaner([&] {
    while (!done.load()) {
      removed += corsa::remove_stale_temporaries(folder);
    }
  });
  for (int round = 0; round < rounds; ++round) {
    write(round);
  }
  done.store(true);
  cleaner.join();
  return removed;
}

/// Failures of the writer counted, the first one's message kept.
struct RaceWriterFailures {
  int count = 0;
  std::string first;

  template <typename Write>
  void run(Write&& write) {
    try {
      write();
    } catch (const corsa::InputError& error) {
      if (count++ == 0) {
        first = error.what();
      }
    }
  }
};

}  // namespace

TEST_CASE("the cleanup of stale temporaries never removes a live writer's temporary",
          "[core][atomic_file][race]") {
  corsa::test::TempDir dir;
  RaceWriterFailures failures;
  const size_t removed = removed_beside_writer(dir.path(), 2000, [&](int round) {
    failures.run([&] {
      corsa::write_file_atomic(dir.path() / "out.csv", "round " + std::to_string(round) + "\n");
    });
  });
  INFO(failures.first);
  CHECK(failures.count == 0);
  CHECK(removed == 0);
  CHECK(corsa::read_file(dir.path() / "out.csv") == "round 1999\n");
  CHECK(dir.entries() == 1);
}

TEST_CASE("the cleanup of stale temporaries never removes a live lock's staging file",
          "[core][output_lock][race]") {
  corsa::test::TempDir dir;
  RaceWriterFailures failures;
  const size_t removed = removed_beside_writer(dir.path(), 1000, [&](int) {
    failures.run([&] { const corsa::OutputLock lock(dir.path()); });
  });
  INFO(failures.first);
  CHECK(failures.count == 0);
  CHECK(removed == 0);
  CHECK(dir.entries() == 0);
}

TEST_CASE("a temporary between its creation and its lock is kept, a killed writer's is removed",
          "[core][atomic_file][race]") {
  corsa::test::TempDir dir;
  const fs::path temporary = dir.path() / ".out.csv.tmp.4242.0";
  {
    // A writer between the two system calls: its share of the folder held, its file created and
    // not yet locked.
    const corsa::detail::FolderTurn creating(dir.path(), corsa::detail::FolderTurn::Kind::kCreate);
    REQUIRE(creating.held());
    std::ofstream(temporary) << "being created";
    CHECK(corsa::remove_stale_temporaries(dir.path()) == 0);
    CHECK(fs::exists(temporary));
  }
  // The writer was killed before it took the lock: nobody holds the folder or the file now.
  CHECK(corsa::remove_stale_temporaries(dir.path()) == 1);
  CHECK(dir.entries() == 0);
}
