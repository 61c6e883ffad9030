#pragma once

// Reading a file a user hands us: regular files only, of bounded size, so that no input makes a
// reader block (a FIFO with no writer, a terminal) or read until memory runs out (/dev/zero, a
// disk image).

#include <cstdint>
#include <filesystem>
#include <string>

namespace corsa {

/// Largest input file Corsa reads, in bytes (512 MiB). 150 times the largest map in the shared
/// samples (Town04.xodr, 3.4 MB); reading and parsing costs about 3 bytes of memory per input
/// byte (Town04: 15 MB peak, `corsa map info` under /usr/bin/time -v), so a file at the cap still
/// fits in about 1.5 GB. Anything larger is a mistake (a disk image, a log), not a map, scenario,
/// rig, suite, golden or sweep file.
inline constexpr uint64_t kMaxInputBytes = uint64_t{512} << 20;

/// Checks that `path` names a regular file (following symbolic links) of at most `max_bytes`:
/// not a folder, FIFO, socket or device. Throws InputError naming the path otherwise, or when it
/// does not exist. For readers that open the file themselves (shapelib).
void check_input_file(const std::filesystem::path& path, uint64_t max_bytes = kMaxInputBytes);

/// Reads a whole regular file of at most `max_bytes` (see check_input_file; the check is made on
/// the opened file, and a file that grows past the cap while read is refused too). Throws
/// InputError naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path, uint64_t max_bytes = kMaxInputBytes);

}  // namespace corsa
