#pragma once

// The preview video encoded while a run's captures are written (DatasetWriter::stream_preview):
// each capture's camera frame and the latest bird's-eye view are composed as write_preview
// composes them from the dataset's files (preview_frame.h) and encoded by libx264 on a thread of
// its own, beside the next captures' rendering, instead of decoding the files and encoding them
// after the last capture. The encoder sees the same frames in the same order, so the same bytes;
// write_preview takes the file only when its frames, size and rate are the ones it would encode.

#include <condition_variable>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "corsa/sensors/preview.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/sensor_system.h"

namespace corsa::sensors::detail {

class H264Writer;

class PreviewStream {
 public:
  /// For the rig's first RGB camera and first bird's-eye camera (as write_preview), writing
  /// under DIR/preview. Encodes nothing when the rig has no RGB camera.
  PreviewStream(const SensorRig& rig, std::filesystem::path dataset);
  /// Stops the encoder and removes its file unless finish() handed it over.
  ~PreviewStream();
  PreviewStream(const PreviewStream&) = delete;
  PreviewStream& operator=(const PreviewStream&) = delete;

  /// The frames of one capture, captures in order (on the thread that runs the captures). Copies
  /// the images it needs; waits only when the encoder is several frames behind.
  void add(std::span<const SensorFrame> frames);
  /// Waits for the encoder and completes the file. Nothing when no camera frame came, when
  /// FFmpeg has no libx264, or when encoding failed (write_preview then encodes the files).
  std::optional<StreamedVideo> finish();

 private:
  /// An 8-bit RGB image as a sensor gave it.
  struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb;
  };
  /// One video frame to compose: the camera's image and time, the latest bird's-eye view.
  struct Shot {
    Image camera;
    double time = 0.0;  ///< s
    std::shared_ptr<const Image> birds_eye;
  };
  void encode_all();
  void encode(const Shot& shot);

  std::string camera_;     ///< sensor names; empty: none in the rig
  std::string birds_eye_;  ///< sensor names; empty: none in the rig
  double fps_ = 10.0;      ///< the camera's rate
  std::filesystem::path file_;
  std::shared_ptr<const Image> latest_birds_eye_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Shot> queue_;
  bool closing_ = false;
  std::thread encoder_;

  // The encoder thread's own (read by finish() once it has joined).
  std::unique_ptr<H264Writer> writer_;
  bool failed_ = false;
  int frames_ = 0;
  int width_ = 0;
  int height_ = 0;
  bool handed_over_ = false;
};

}  // namespace corsa::sensors::detail
