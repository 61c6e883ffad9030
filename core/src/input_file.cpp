#include "corsa/core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "corsa/core/diagnostic.h"

namespace corsa {
namespace {

[[noreturn]] void input_error(const std::filesystem::path& path, const std::string& message) {
  throw InputError(make_error(path.string(), 0, message));
}

/// Closes a descriptor when it goes out of scope.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) {
      ::close(fd_);
    }
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

const char* kind_of(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

/// The checks of check_input_file on what stat says of the file.
void check_status(const std::filesystem::path& path, const struct stat& status,
                  uint64_t max_bytes) {
  if (S_ISDIR(status.st_mode)) {
    input_error(path, "is a folder, not a file");
  }
  if (!S_ISREG(status.st_mode)) {
    input_error(path, std::string("is ") + kind_of(status.st_mode) +
                          "; Corsa reads its inputs from regular files only");
  }
  if (static_cast<uint64_t>(status.st_size) > max_bytes) {
    input_error(path, "is " + std::to_string(status.st_size) + " bytes, more than the " +
                          mebibytes(max_bytes) + " Corsa reads from one input file");
  }
}

}  // namespace

void check_input_file(const std::filesystem::path& path, uint64_t max_bytes) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    input_error(path, std::string("cannot open file (") + std::strerror(errno) + ")");
  }
  check_status(path, status, max_bytes);
}

std::string read_file(const std::filesystem::path& path, uint64_t max_bytes) {
  // O_NONBLOCK: opening a FIFO without a writer would otherwise block before fstat can refuse it.
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) {
    input_error(path, std::string("cannot open file (") + std::strerror(errno) + ")");
  }
  struct stat status {};
  if (::fstat(fd.get(), &status) != 0) {
    input_error(path, std::string("cannot read file (") + std::strerror(errno) + ")");
  }
  check_status(path, status, max_bytes);
  std::string content(static_cast<size_t>(status.st_size), '\0');
  size_t size = 0;
  while (true) {
    // Past the size fstat gave, the file may have grown since: a small read says whether it did
    // before the string grows (growing it first would zero-fill memory for every file read).
    const bool past_end = size == content.size();
    if (past_end && size >= max_bytes) {
      char probe = 0;
      const ssize_t more = ::read(fd.get(), &probe, 1);
      if (more > 0) {
        input_error(path, "grew past the " + mebibytes(max_bytes) +
                              " Corsa reads from one input file while being read");
      }
      break;
    }
    char grown[4096];
    const size_t room =
        past_end ? std::min<uint64_t>(sizeof grown, max_bytes - size) : content.size() - size;
    const ssize_t got = ::read(fd.get(), past_end ? grown : content.data() + size, room);
    if (got < 0) {
      if (errno == EINTR) continue;
      input_error(path, std::string("read failed (") + std::strerror(errno) + ")");
    }
    if (got == 0) break;
    if (past_end) content.append(grown, static_cast<size_t>(got));
    size += static_cast<size_t>(got);
  }
  content.resize(size);
  return content;
}

}  // namespace corsa
