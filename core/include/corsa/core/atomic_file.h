#pragma once

#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include "corsa/core/input_file.h"  // read_file, which users of this header expect

namespace corsa {

/// An output file that appears under its name only when complete.
///
/// Writes go to a hidden temporary file in the same directory (".<name>.tmp.<pid>.<n>"); commit()
/// flushes, closes and renames it over the target, which is atomic on POSIX file systems. If the
/// object is destroyed without commit() (an exception, an early return), the temporary is removed
/// and any earlier file under the target name is left untouched. Never a half-written output.
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
  std::ofstream out_;
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

/// Writes `content` to `target` atomically (see AtomicFile).
void write_file_atomic(const std::filesystem::path& target, std::string_view content,
                       bool binary = false);

}  // namespace corsa
