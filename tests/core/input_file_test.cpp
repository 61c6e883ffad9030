#include "corsa/core/input_file.h"

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "corsa/core/diagnostic.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;

std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const corsa::InputError& error) {
    return error.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("read_file reads a regular file whole, at the size cap too", "[core][input]") {
  corsa::test::TempDir dir;
  const fs::path file = dir.path() / "a.txt";
  std::ofstream(file, std::ios::binary) << std::string(1000, 'x');
  CHECK(corsa::read_file(file) == std::string(1000, 'x'));
  CHECK(corsa::read_file(file, 1000).size() == 1000);
  CHECK_NOTHROW(corsa::check_input_file(file, 1000));
}

TEST_CASE("read_file refuses a file past its cap, naming the file and the cap", "[core][input]") {
  corsa::test::TempDir dir;
  const fs::path file = dir.path() / "big.xodr";
  std::ofstream(file, std::ios::binary) << std::string((3 << 20) + 1, ' ');
  const std::string expected =
      file.string() +
      ": error: is 3145729 bytes, more than the 3 MiB Corsa reads from one input "
      "file";
  CHECK(error_of([&] { corsa::read_file(file, 3 << 20); }) == expected);
  CHECK(error_of([&] { corsa::check_input_file(file, 3 << 20); }) == expected);
}

TEST_CASE("read_file refuses FIFOs, devices and folders without blocking", "[core][input]") {
  corsa::test::TempDir dir;
  const fs::path fifo = dir.path() / "pipe.xosc";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK(error_of([&] { corsa::read_file(fifo); }) ==
        fifo.string() +
            ": error: is a FIFO (named pipe); Corsa reads its inputs from regular files only");
  CHECK(error_of([&] { corsa::check_input_file(fifo); }).find("is a FIFO") != std::string::npos);
  CHECK(error_of([] { corsa::read_file("/dev/zero"); }) ==
        "/dev/zero: error: is a character device; Corsa reads its inputs from regular files only");
  CHECK(error_of([&] { corsa::read_file(dir.path()); }) ==
        dir.path().string() + ": error: is a folder, not a file");
  CHECK(error_of([&] {
          corsa::read_file(dir.path() / "missing");
        }).find("cannot open file (No such file or directory)") != std::string::npos);
}

TEST_CASE("read_file reads files whose size stat does not know", "[core][input]") {
  // /proc files report size 0 and still have content.
  CHECK_FALSE(corsa::read_file("/proc/self/status").empty());
}
