#pragma once

// Creating a temporary and deciding that one is stale, ordered against each other: the parts
// AtomicFile, OutputLock and remove_stale_temporaries share (in `detail`: not for other callers).
//
// A temporary is created (open with O_CREAT) and then locked (flock), two system calls; a
// cleanup that looked in between would find an unlocked temporary of a live writer and remove
// it. So each step holds a flock of the folder itself: creating a temporary and locking it
// happen under a shared one, and the cleanup decides under an exclusive one. A temporary that
// the cleanup finds unlocked while it holds the folder exclusively was left by a writer that is
// gone (killed between the two calls, or later): those are still removed.

#include <filesystem>

namespace corsa::detail {

/// A flock(2) of a folder, held while the object lives. Not held (held() false) when the folder
/// cannot be opened or locked; a shared lock is waited for, an exclusive one tried for a while.
class FolderTurn {
 public:
  enum class Kind { kCreate, kCleanup };
  FolderTurn(const std::filesystem::path& folder, Kind kind);
  FolderTurn(const FolderTurn&) = delete;
  FolderTurn& operator=(const FolderTurn&) = delete;
  ~FolderTurn();
  bool held() const { return held_; }

 private:
  int descriptor_ = -1;
  bool held_ = false;
};

/// A new temporary beside `target` (".<name>.tmp.<pid>.<n>"), opened for writing with
/// O_CREAT | O_EXCL | O_NOFOLLOW and already under its exclusive flock when any cleanup can see
/// it. `descriptor` is -1 (errno set) on failure; a name already taken is skipped.
struct LockedTemporary {
  std::filesystem::path path;
  int descriptor = -1;
};
LockedTemporary create_locked_temporary(const std::filesystem::path& target, unsigned mode);

}  // namespace corsa::detail
