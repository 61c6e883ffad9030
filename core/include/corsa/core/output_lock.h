#pragma once

// One writer per output folder. Two runs writing into the same folder at once would interleave
// their files (a sweep's variants, a dataset's frames), so a run that writes a folder holds its
// lock for as long as it writes.

#include <filesystem>
#include <string>

namespace corsa {

/// The lock of an output folder: the file `<folder>/.corsa.lock`, holding the owner's process id
/// and host name, made with O_EXCL (it appears whole, through link(2), or not at all) and kept
/// under an exclusive flock(2) while the owner lives. A lock whose flock is free is stale (its
/// owner was killed) and is taken over; a held one refuses the second writer. Released (the
/// file removed) when the object is destroyed.
class OutputLock {
 public:
  static constexpr const char* kFileName = ".corsa.lock";

  /// Locks `folder`, which must exist. Throws InputError naming the folder when another live
  /// process holds it (with its pid and host) or when the lock file cannot be made.
  explicit OutputLock(const std::filesystem::path& folder);
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  int descriptor_ = -1;
};

}  // namespace corsa
