#include "corsa/core/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "corsa/core/diagnostic.h"
#include "corsa/core/locked_temporary.h"

namespace corsa {

bool is_temporary_name(std::string_view name) {
  if (name.size() < 9 || name.front() != '.') {
    return false;
  }
  const size_t last_dot = name.rfind('.');
  const size_t pid_dot =
      last_dot == std::string_view::npos ? last_dot : name.rfind('.', last_dot - 1);
  if (pid_dot == std::string_view::npos || pid_dot < 5 || name.substr(pid_dot - 4, 4) != ".tmp") {
    return false;
  }
  const auto digits = [&](size_t from, size_t to) {
    return to > from && std::all_of(name.begin() + static_cast<std::ptrdiff_t>(from),
                                    name.begin() + static_cast<std::ptrdiff_t>(to),
                                    [](char c) { return c >= '0' && c <= '9'; });
  };
  return digits(pid_dot + 1, last_dot) && digits(last_dot + 1, name.size());
}

namespace {

/// Removes `path` when it is a regular file no live process holds locked (see AtomicFile).
bool remove_if_stale(const std::filesystem::path& path) {
  // A writer creates and locks its temporary under its share of the folder: while the cleanup
  // holds the folder alone, an unlocked temporary is one whose writer is gone.
  const detail::FolderTurn turn(path.parent_path(), detail::FolderTurn::Kind::kCleanup);
  if (!turn.held()) {
    return false;  // left for a later cleanup
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    return false;
  }
  bool removed = false;
  struct stat opened {};
  struct stat named {};
  // The lock is free once its owner died (or renamed and closed it, in which case the name no
  // longer leads to this file).
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::fstat(fd, &opened) == 0 && S_ISREG(opened.st_mode) &&
      ::lstat(path.c_str(), &named) == 0 && named.st_ino == opened.st_ino &&
      named.st_dev == opened.st_dev) {
    removed = ::unlink(path.c_str()) == 0;
  }
  ::close(fd);
  return removed;
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

namespace detail {

/// An output stream buffer over a file descriptor (std::ofstream cannot open with O_EXCL |
/// O_NOFOLLOW, nor hand out its descriptor for flock).
class DescriptorStreamBuf final : public std::streambuf {
 public:
  explicit DescriptorStreamBuf(int fd) : fd_(fd) { setp(buffer_.data(), buffer_.data() + kSize); }
  bool failed() const { return failed_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) {
      return traits_type::eof();
    }
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }
  std::streamsize xsputn(const char* data, std::streamsize count) override {
    if (count >= static_cast<std::streamsize>(kSize)) {
      // Large blocks go straight to the file.
      if (!drain() || !write_all(data, static_cast<size_t>(count))) {
        return 0;
      }
      return count;
    }
    return std::streambuf::xsputn(data, count);
  }

 private:
  static constexpr size_t kSize = 1 << 16;

  bool drain() {
    const auto pending = static_cast<size_t>(pptr() - pbase());
    const bool ok = write_all(pbase(), pending);
    setp(buffer_.data(), buffer_.data() + kSize);
    return ok;
  }
  bool write_all(const char* data, size_t size) {
    while (size > 0 && !failed_) {
      const ssize_t written = ::write(fd_, data, size);
      if (written < 0 && errno == EINTR) {
        continue;
      }
      if (written <= 0) {
        failed_ = true;
        break;
      }
      data += written;
      size -= static_cast<size_t>(written);
    }
    return !failed_;
  }

  int fd_;
  bool failed_ = false;
  std::array<char, kSize> buffer_{};
};

}  // namespace detail

AtomicFile::AtomicFile(std::filesystem::path target, bool /*binary*/)
    : target_(std::move(target)), out_(nullptr) {
  check_output_file(target_);
  // A folder made here can vanish before the temporary is in it (a writer beside this one that
  // failed removes the empty folders it made): it is made again.
  detail::LockedTemporary made;
  for (int attempt = 0; attempt < 3; ++attempt) {
    for (auto& folder : create_output_folders(target_.parent_path(), target_)) {
      if (std::find(created_folders_.begin(), created_folders_.end(), folder) ==
          created_folders_.end()) {
        created_folders_.push_back(std::move(folder));
      }
    }
    made = detail::create_locked_temporary(target_, 0666);
    if (made.descriptor >= 0 || errno != ENOENT) {
      break;
    }
  }
  if (made.descriptor < 0) {
    const std::string reason = std::strerror(errno);
    std::error_code ignored;
    for (const auto& folder : created_folders_) {
      std::filesystem::remove(folder, ignored);
    }
    throw InputError(make_error(target_.string(), 0, "cannot create output file (" + reason + ")"));
  }
  temporary_ = std::move(made.path);
  descriptor_ = made.descriptor;
  buffer_ = std::make_unique<detail::DescriptorStreamBuf>(descriptor_);
  out_.rdbuf(buffer_.get());
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    // Innermost first; remove() leaves a folder that meanwhile holds something else.
    for (const auto& folder : created_folders_) {
      std::filesystem::remove(folder, ignored);
    }
  }
  if (descriptor_ >= 0) {
    ::close(descriptor_);
  }
}

void AtomicFile::commit() {
  if (committed_) {
    return;
  }
  out_.flush();
  std::error_code error;
  if (!out_ || buffer_->failed()) {
    std::filesystem::remove(temporary_, error);
    throw InputError(make_error(target_.string(), 0, "write failed (disk full?)"));
  }
  // Renamed while still open and locked, so that no cleanup takes it for a stale temporary.
  std::filesystem::rename(temporary_, target_, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw InputError(
        make_error(target_.string(), 0, "cannot move output into place (" + error.message() + ")"));
  }
  committed_ = true;
  ::close(descriptor_);
  descriptor_ = -1;
}

void create_folder_inside(const std::filesystem::path& root,
                          const std::filesystem::path& relative) {
  std::filesystem::path folder = root;
  for (const auto& part : relative) {
    if (part.empty() || part == ".") {
      continue;
    }
    if (part == ".." || part.has_root_directory()) {
      output_error(root / relative, "leaves the output folder " + root.string());
    }
    folder /= part;
    struct stat status {};
    if (::lstat(folder.c_str(), &status) != 0) {
      if (errno == ENOENT && ::mkdir(folder.c_str(), 0777) == 0) {
        continue;
      }
      if (errno != EEXIST || ::lstat(folder.c_str(), &status) != 0) {
        output_error(folder, std::string("cannot create folder (") + std::strerror(errno) + ")");
      }
    }
    if (S_ISLNK(status.st_mode)) {
      output_error(folder, "is a symbolic link inside the output folder " + root.string() +
                               "; Corsa writes only into folders that are really there");
    }
    if (!S_ISDIR(status.st_mode)) {
      output_error(folder, "is in the way of an output folder (it is not a folder)");
    }
  }
}

size_t remove_stale_temporaries(const std::filesystem::path& folder, int depth) {
  size_t removed = 0;
  std::error_code error;
  const auto visit = [&](const std::filesystem::directory_entry& entry) {
    std::error_code ignored;
    if (is_temporary_name(entry.path().filename().string()) && entry.is_regular_file(ignored) &&
        !entry.is_symlink(ignored) && remove_if_stale(entry.path())) {
      ++removed;
    }
  };
  for (std::filesystem::recursive_directory_iterator
           it(folder, std::filesystem::directory_options::skip_permission_denied, error),
       end;
       !error && it != end; it.increment(error)) {
    if (it.depth() >= depth) {
      it.disable_recursion_pending();
    }
    visit(*it);
  }
  return removed;
}

void write_file_atomic(const std::filesystem::path& target, std::string_view content, bool binary) {
  AtomicFile file(target, binary);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

}  // namespace corsa
