#include "corsa/core/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "corsa/core/diagnostic.h"
#include "corsa/core/locked_temporary.h"
#include "corsa/core/strings.h"

namespace corsa {
namespace {

[[noreturn]] void lock_error(const std::filesystem::path& folder, const std::string& message) {
  throw InputError(make_error(folder.string(), 0, message));
}

std::string host_name() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0) {
    return "?";
  }
  return name.data();
}

/// What a held lock file says of its owner ("pid 123 on host x"), for the message.
std::string owner_of(int fd) {
  std::array<char, 300> text{};
  const ssize_t size = ::pread(fd, text.data(), text.size() - 1, 0);
  const std::string owner(trim(std::string_view(text.data(), size > 0 ? size_t(size) : 0)));
  return owner.empty() ? "another process" : clip(owner);
}

enum class Existing { kGone, kRemovedStale, kHeld };

/// How long a held lock is watched for being a stale one that another process is removing.
constexpr int kJudgeTries = 100;
constexpr auto kJudgePause = std::chrono::milliseconds(2);

/// Whether the name `path` still leads to the open file `fd`.
bool names_file(const std::filesystem::path& path, int fd) {
  struct stat opened {};
  struct stat named {};
  return ::fstat(fd, &opened) == 0 && ::lstat(path.c_str(), &named) == 0 &&
         opened.st_ino == named.st_ino && opened.st_dev == named.st_dev;
}

/// Looks at the lock file of another process: removes it when stale, else says who holds it.
Existing check_existing(const std::filesystem::path& lock, std::string& owner) {
  const int fd = ::open(lock.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    return Existing::kGone;
  }
  // A live owner holds the flock for its whole run; another process judging the same stale lock
  // holds it for a few system calls and then removes it: that one is waited for, and the name
  // then leads elsewhere or nowhere.
  bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  for (int attempt = 0; !free && attempt < kJudgeTries && names_file(lock, fd); ++attempt) {
    std::this_thread::sleep_for(kJudgePause);
    free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  }
  Existing result = Existing::kGone;
  if (!names_file(lock, fd)) {
    result = Existing::kGone;  // replaced or removed meanwhile: try again
  } else if (!free) {
    owner = owner_of(fd);
    result = Existing::kHeld;
  } else {
    // Free: its owner is gone. Removed while we hold its flock, so that others judging it wait.
    ::unlink(lock.c_str());
    result = Existing::kRemovedStale;
  }
  ::close(fd);
  return result;
}

}  // namespace

OutputLock::OutputLock(const std::filesystem::path& folder) : file_(folder / kFileName) {
  // The lock is written and locked under a temporary name first and then linked to its name, so
  // that the name never leads to a lock file that is not yet held. The temporary is an AtomicFile
  // one (locked before any cleanup can see it), so a killed process's is cleaned like theirs.
  const detail::LockedTemporary made = detail::create_locked_temporary(file_, 0644);
  if (made.descriptor < 0) {
    lock_error(folder, std::string("cannot lock the output folder (") + std::strerror(errno) + ")");
  }
  descriptor_ = made.descriptor;
  const std::filesystem::path& staging = made.path;
  const std::string pid = std::to_string(::getpid());
  const std::string owner = "pid " + pid + " on host " + host_name() + "\n";
  const bool written =
      ::write(descriptor_, owner.data(), owner.size()) == static_cast<ssize_t>(owner.size());
  for (int attempt = 0; written && attempt < 10; ++attempt) {
    if (::link(staging.c_str(), file_.c_str()) == 0) {
      ::unlink(staging.c_str());
      return;
    }
    if (errno != EEXIST) {
      break;
    }
    std::string holder;
    if (check_existing(file_, holder) == Existing::kHeld) {
      ::unlink(staging.c_str());
      ::close(descriptor_);
      descriptor_ = -1;
      lock_error(folder, "another corsa (" + holder +
                             ") is writing into this folder; wait for it, or choose another "
                             "output folder (if no such process runs, remove " +
                             file_.string() + ")");
    }
  }
  const std::string reason = std::strerror(errno);
  ::unlink(staging.c_str());
  ::close(descriptor_);
  descriptor_ = -1;
  lock_error(folder, "cannot lock the output folder (" + reason + ")");
}

OutputLock::~OutputLock() {
  if (descriptor_ >= 0) {
    // Removed while still held, so that no other process takes the file for a stale lock.
    ::unlink(file_.c_str());
    ::close(descriptor_);
  }
}

}  // namespace corsa
