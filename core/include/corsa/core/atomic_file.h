#pragma once

#include <filesystem>
#include <fstream>
#include <string_view>

namespace corsa {

/// An output file that appears under its name only when complete.
///
/// Writes go to a hidden temporary file in the same directory (".<name>.tmp.<pid>.<n>"); commit()
/// flushes, closes and renames it over the target, which is atomic on POSIX file systems. If the
/// object is destroyed without commit() (an exception, an early return), the temporary is removed
/// and any earlier file under the target name is left untouched. Never a half-written output.
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
  bool committed_ = false;
};

/// Writes `content` to `target` atomically (see AtomicFile).
void write_file_atomic(const std::filesystem::path& target, std::string_view content,
                       bool binary = false);

/// Reads a whole file; throws InputError naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace corsa
