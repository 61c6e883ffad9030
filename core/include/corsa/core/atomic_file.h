#pragma once

#include <filesystem>
#include <memory>
#include <ostream>
#include <string_view>
#include <vector>

#include "corsa/core/input_file.h"  // read_file, which users of this header expect

namespace corsa {

namespace detail {
class DescriptorStreamBuf;
}

/// An output file that appears under its name only when complete.
///
/// Writes go to a hidden temporary file in the same directory (".<name>.tmp.<pid>.<n>"); commit()
/// flushes and renames it over the target, which is atomic on POSIX file systems. If the object
/// is destroyed without commit() (an exception, an early return), the temporary is removed and
/// any earlier file under the target name is left untouched. Never a half-written output.
///
/// The temporary is created with O_EXCL | O_NOFOLLOW (a file or symbolic link planted under its
/// predictable name is never written through) and held under an exclusive flock(2) until it has
/// been renamed or removed, so that remove_stale_temporaries can tell the temporaries of a
/// killed process (lock free) from those of a live one.
///
/// Missing folders on the way to the target are created (like `mkdir -p`, the way every Corsa
/// output behaves, folders such as `sweep -o` included); when the file is not committed, the
/// folders this object created are removed again if still empty. A target that is a folder, or a
/// path through a regular file, is an InputError naming the target (see check_output_file).
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target, bool binary = false);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// The stream to write to. A failed write is reported by commit().
  std::ostream& stream() { return out_; }
  /// Finishes the file: flush, close, rename into place. Throws InputError (naming the file) on
  /// any I/O failure; the temporary is then removed.
  void commit();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int descriptor_ = -1;
  std::unique_ptr<detail::DescriptorStreamBuf> buffer_;
  std::ostream out_;
  std::vector<std::filesystem::path> created_folders_;  ///< innermost first
  bool committed_ = false;
};

/// Checks before any work is done that `target` can become an output file: it is not an
/// existing folder and no existing part of its folder path is something other than a folder.
/// Missing folders are fine (AtomicFile creates them). Throws InputError naming the target.
void check_output_file(const std::filesystem::path& target);

/// The same for an output folder (`sweep -o`, `test -o`, a dataset): it is a folder or absent,
/// and no existing part of its path is a regular file.
void check_output_folder(const std::filesystem::path& folder);

/// Creates the missing folders of `folder` (like `mkdir -p`) and returns those it created,
/// innermost first. Throws InputError naming `target` (the output being written) on failure.
std::vector<std::filesystem::path> create_output_folders(const std::filesystem::path& folder,
                                                         const std::filesystem::path& target);

/// Whether a file name has the form of an AtomicFile temporary: ".<name>.tmp.<pid>.<n>".
bool is_temporary_name(std::string_view name);

/// Removes the temporaries of AtomicFile (".<name>.tmp.<pid>.<n>") that a killed process left in
/// `folder` and in the folders up to `depth` levels below it (symbolic links not followed): those
/// no live AtomicFile holds locked. Returns how many were removed. Never throws: a temporary
/// that cannot be removed stays.
size_t remove_stale_temporaries(const std::filesystem::path& folder, int depth = 0);

/// Makes `root / relative` a folder, creating its missing parts one by one, and refuses any part
/// below `root` that is a symbolic link or not a folder: what is written there then stays inside
/// `root`, never going through a link planted in it. `relative` must not leave `root` ("..",
/// absolute). Throws InputError naming the offending part.
void create_folder_inside(const std::filesystem::path& root, const std::filesystem::path& relative);

/// Writes `content` to `target` atomically (see AtomicFile).
void write_file_atomic(const std::filesystem::path& target, std::string_view content,
                       bool binary = false);

}  // namespace corsa
