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

[[noreturn]] void output_error(const std::filesystem::path& target, const std::string& message) {
  throw InputError(make_error(target.string(), 0, message));
}

/// Fails when an existing part of `folder`'s path is not a folder (a path through a file).
void check_folder_path(const std::filesystem::path& folder, const std::filesystem::path& target) {
  std::error_code error;
  for (std::filesystem::path part = folder; !part.empty(); part = part.parent_path()) {
    const auto status = std::filesystem::status(part, error);
    if (std::filesystem::exists(status)) {
      if (!std::filesystem::is_directory(status)) {
        output_error(target, "cannot create output: '" + part.string() + "' is not a folder");
      }
      return;  // the rest of the path exists and leads here
    }
    if (part == part.parent_path()) {
      return;
    }
  }
}

}  // namespace

void check_output_file(const std::filesystem::path& target) {
  std::error_code error;
  if (std::filesystem::is_directory(target, error)) {
    output_error(target, "is a folder; an output file cannot replace it");
  }
  check_folder_path(target.parent_path(), target);
}

void check_output_folder(const std::filesystem::path& folder) { check_folder_path(folder, folder); }

std::vector<std::filesystem::path> create_output_folders(const std::filesystem::path& folder,
                                                         const std::filesystem::path& target) {
  std::vector<std::filesystem::path> created;
  std::error_code error;
  for (std::filesystem::path part = folder; !part.empty() && !std::filesystem::exists(part, error);
       part = part.parent_path()) {
    created.push_back(part);
    if (part == part.parent_path()) {
      break;
    }
  }
  if (created.empty()) {
    return created;
  }
  check_folder_path(folder, target);
  std::filesystem::create_directories(folder, error);
  if (error && !std::filesystem::is_directory(folder)) {
    output_error(target,
                 "cannot create folder '" + folder.string() + "' (" + error.message() + ")");
  }
  return created;
}

AtomicFile::AtomicFile(std::filesystem::path target, bool binary)
    : target_(std::move(target)), temporary_(temporary_name_for(target_)) {
  check_output_file(target_);
  created_folders_ = create_output_folders(target_.parent_path(), target_);
  const auto mode =
      std::ios::out | std::ios::trunc | (binary ? std::ios::binary : std::ios::openmode{});
  out_.open(temporary_, mode);
  if (!out_) {
    const std::string reason = std::strerror(errno);
    std::error_code ignored;
    for (const auto& folder : created_folders_) {
      std::filesystem::remove(folder, ignored);
    }
    throw InputError(make_error(target_.string(), 0, "cannot create output file (" + reason + ")"));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    // Innermost first; remove() leaves a folder that meanwhile holds something else.
    for (const auto& folder : created_folders_) {
      std::filesystem::remove(folder, ignored);
    }
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

}  // namespace corsa
