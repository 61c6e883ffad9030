#pragma once

// The preview video's H.264 encoder: libx264 through FFmpeg's libraries (libavcodec, libavformat,
// libswscale), called directly so that the encoder's preset and rate control can be chosen.
// OpenCV's VideoWriter opens libx264 with no options at all: its default `medium` preset, at a
// bit rate OpenCV picks.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>

namespace corsa::sensors::detail {

class H264Writer {
 public:
  /// Opens an MP4 file at `path` for frames of `size` (even width and height) at `fps` frames a
  /// second. Returns nullptr when this FFmpeg has no libx264 encoder or the file cannot be
  /// opened (the caller falls back to OpenCV's writers).
  static std::unique_ptr<H264Writer> open(const std::filesystem::path& path, cv::Size size,
                                          double fps);
  /// Whether frame rates `a` and `b` (frames a second) open the same stream: the encoder keeps
  /// the rate as a fraction (open()), so rates that round to one fraction give the same file.
  static bool same_frame_rate(double a, double b);
  ~H264Writer();
  H264Writer(const H264Writer&) = delete;
  H264Writer& operator=(const H264Writer&) = delete;

  /// Encodes one 8-bit BGR frame of the size given to open(). Throws InputError when the encoder
  /// or the file fails.
  void write(const cv::Mat& bgr);
  /// Flushes the encoder and completes the file. Throws InputError when that fails.
  void finish();

 private:
  struct Codec;
  explicit H264Writer(std::unique_ptr<Codec> codec);
  void send(bool flush);
  std::unique_ptr<Codec> codec_;
};

}  // namespace corsa::sensors::detail
