#include "corsa/core/locked_temporary.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <sstream>
#include <thread>

namespace corsa::detail {
namespace {

/// How long the cleanup waits for writers to finish creating their temporaries in a folder
/// (each holds it for two system calls) before leaving a candidate to a later cleanup.
constexpr int kCleanupTries = 1000;
constexpr auto kCleanupPause = std::chrono::microseconds(200);

std::filesystem::path temporary_name_for(const std::filesystem::path& target) {
  // A process-wide counter only makes temporary names unique; it never affects file contents.
  static std::atomic<unsigned long> counter{0};
  std::ostringstream name;
  name << '.' << target.filename().string() << ".tmp." << ::getpid() << '.' << counter++;
  return target.parent_path() / name.str();
}

}  // namespace

FolderTurn::FolderTurn(const std::filesystem::path& folder, Kind kind) {
  const std::filesystem::path where = folder.empty() ? std::filesystem::path(".") : folder;
  descriptor_ = ::open(where.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (descriptor_ < 0) {
    return;
  }
  if (kind == Kind::kCreate) {
    int result = 0;
    do {
      result = ::flock(descriptor_, LOCK_SH);
    } while (result != 0 && errno == EINTR);
    held_ = result == 0;
    return;
  }
  // Tried rather than waited for: a stream of writers could hold the folder shared for long.
  for (int attempt = 0; attempt < kCleanupTries; ++attempt) {
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) == 0) {
      held_ = true;
      return;
    }
    if (errno != EWOULDBLOCK && errno != EINTR) {
      return;  // a file system without folder locks: no temporary is judged stale there
    }
    std::this_thread::sleep_for(kCleanupPause);
  }
}

FolderTurn::~FolderTurn() {
  if (descriptor_ >= 0) {
    ::close(descriptor_);  // releases the flock
  }
}

LockedTemporary create_locked_temporary(const std::filesystem::path& target, unsigned mode) {
  LockedTemporary made;
  int error = 0;
  {
    const FolderTurn turn(target.parent_path(), FolderTurn::Kind::kCreate);
    // A name taken already (a temporary of a killed process whose pid came round again, or of a
    // process with the same pid on another host sharing the folder) is skipped.
    for (int attempt = 0; attempt < 100 && made.descriptor < 0; ++attempt) {
      made.path = temporary_name_for(target);
      made.descriptor =
          ::open(made.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                 static_cast<mode_t>(mode));
      if (made.descriptor < 0 && errno != EEXIST) {
        break;
      }
    }
    error = errno;
    if (made.descriptor >= 0) {
      // Held until the temporary is renamed or removed: a free lock marks a stale temporary.
      // Nobody else holds this new file, so only a file system without flock can refuse it.
      ::flock(made.descriptor, LOCK_EX | LOCK_NB);
    }
  }
  errno = error;
  return made;
}

}  // namespace corsa::detail
