#include "corsa/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <system_error>

#include "corsa/core/diagnostic.h"

namespace corsa {
namespace {

std::filesystem::path temporary_name_for(const std::filesystem::path& target) {
  // A process-wide counter only makes temporary names unique; it never affects file contents.
  static std::atomic<unsigned long> counter{0};
  std::ostringstream name;
  name << '.' << target.filename().string() << ".tmp." << ::getpid() << '.' << counter++;
  return target.parent_path() / name.str();
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target, bool binary)
    : target_(std::move(target)), temporary_(temporary_name_for(target_)) {
  const auto mode =
      std::ios::out | std::ios::trunc | (binary ? std::ios::binary : std::ios::openmode{});
  out_.open(temporary_, mode);
  if (!out_) {
    throw InputError(
        make_error(target_.string(), 0,
                   std::string("cannot create output file (") + std::strerror(errno) + ")"));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::commit() {
  if (committed_) {
    return;
  }
  out_.flush();
  const bool write_ok = static_cast<bool>(out_);
  out_.close();
  std::error_code error;
  if (!write_ok || out_.fail()) {
    std::filesystem::remove(temporary_, error);
    throw InputError(make_error(target_.string(), 0, "write failed (disk full?)"));
  }
  std::filesystem::rename(temporary_, target_, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw InputError(
        make_error(target_.string(), 0, "cannot move output into place (" + error.message() + ")"));
  }
  committed_ = true;
}

void write_file_atomic(const std::filesystem::path& target, std::string_view content, bool binary) {
  AtomicFile file(target, binary);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

std::string read_file(const std::filesystem::path& path) {
  // An ifstream opens a directory without complaint and then reads nothing, which a parser would
  // report as an empty document.
  std::error_code status_error;
  if (std::filesystem::is_directory(path, status_error)) {
    throw InputError(make_error(path.string(), 0, "is a folder, not a file"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(make_error(path.string(), 0,
                                std::string("cannot open file (") + std::strerror(errno) + ")"));
  }
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) {
    throw InputError(make_error(path.string(), 0, "read failed"));
  }
  return content.str();
}

}  // namespace corsa
