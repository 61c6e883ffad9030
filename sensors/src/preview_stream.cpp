#include "preview_stream.h"

#include <opencv2/imgproc.hpp>
#include <system_error>

#include "h264_writer.h"
#include "preview_frame.h"

namespace corsa::sensors::detail {
namespace {

/// Captures the encoder may fall behind before add() waits (each holds about 4 MB of images).
constexpr size_t kPreviewQueuedCaptures = 3;

}  // namespace

PreviewStream::PreviewStream(const SensorRig& rig, std::filesystem::path dataset)
    : file_(std::move(dataset) / "preview" / ".camera_birds_eye.stream.mp4") {
  for (const SensorSpec& s : rig.sensors) {
    if (camera_.empty() && s.kind == SensorKind::kRgbCamera) {
      camera_ = s.name;
      fps_ = s.rate_hz;
    }
    if (birds_eye_.empty() && s.kind == SensorKind::kBirdsEyeCamera) {
      birds_eye_ = s.name;
    }
  }
}

PreviewStream::~PreviewStream() {
  {
    const std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (encoder_.joinable()) {
    encoder_.join();
  }
  writer_.reset();
  if (!handed_over_) {
    std::error_code ignored;
    std::filesystem::remove(file_, ignored);
  }
}

void PreviewStream::add(std::span<const SensorFrame> frames) {
  if (camera_.empty()) {
    return;
  }
  const auto copy = [](const std::vector<uint8_t>& rgb, int width, int height) {
    return Image{width, height, rgb};
  };
  // The bird's-eye view first: write_preview shows the latest one at or before the camera's
  // tick, so one of the same capture.
  for (const SensorFrame& f : frames) {
    if (f.sensor == birds_eye_) {
      latest_birds_eye_ = std::make_shared<const Image>(
          copy(f.birds_eye.rgb, f.birds_eye.width, f.birds_eye.height));
    }
  }
  for (const SensorFrame& f : frames) {
    if (f.sensor != camera_) {
      continue;
    }
    // frames.csv writes the time in its shortest round-trip form, so write_preview reads back
    // this same double.
    Shot shot{copy(f.camera.rgb, f.camera.width, f.camera.height), f.time, latest_birds_eye_};
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return queue_.size() < kPreviewQueuedCaptures; });
    queue_.push_back(std::move(shot));
    if (!encoder_.joinable()) {
      // Started by the thread that runs the captures (and would otherwise encode the files after
      // the run): the encoder runs with its floating-point environment.
      encoder_ = std::thread([this] { encode_all(); });
    }
    lock.unlock();
    changed_.notify_all();
  }
}

void PreviewStream::encode_all() {
  for (;;) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return closing_ || !queue_.empty(); });
    if (queue_.empty()) {
      return;  // closing, and everything added is encoded
    }
    const Shot shot = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    changed_.notify_all();
    if (!failed_) {
      try {
        encode(shot);
      } catch (...) {  // NOLINT(bugprone-empty-catch): write_preview encodes the files instead
        failed_ = true;
      }
    }
  }
}

void PreviewStream::encode(const Shot& shot) {
  // cv::Mat over the copied bytes (read only), turned into the BGR the dataset's PNGs decode to.
  const auto bgr = [](const Image& image) {
    cv::Mat out;
    cv::cvtColor(
        cv::Mat(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.rgb.data())), out,
        cv::COLOR_RGB2BGR);
    return out;
  };
  const cv::Mat camera = bgr(shot.camera);
  if (frames_ == 0) {
    std::error_code error;
    std::filesystem::create_directories(file_.parent_path(), error);
    const cv::Size size =
        preview_video_size(fit_height(camera, kPreviewHeight).cols, !birds_eye_.empty());
    width_ = size.width;
    height_ = size.height;
    writer_ = H264Writer::open(file_, size, fps_);
    if (writer_ == nullptr) {
      failed_ = true;  // no libx264: write_preview falls back to OpenCV's writers
      return;
    }
  }
  const cv::Mat top = shot.birds_eye ? bgr(*shot.birds_eye) : cv::Mat();
  writer_->write(compose_preview_frame(camera, shot.time, top, cv::Size(width_, height_)));
  ++frames_;
}

std::optional<StreamedVideo> PreviewStream::finish() {
  {
    const std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (encoder_.joinable()) {
    encoder_.join();
  }
  if (writer_ == nullptr || failed_ || frames_ == 0) {
    return std::nullopt;
  }
  try {
    writer_->finish();
  } catch (...) {  // NOLINT(bugprone-empty-catch): write_preview encodes the files instead
    return std::nullopt;
  }
  writer_.reset();
  handed_over_ = true;
  return StreamedVideo{file_, width_, height_, frames_, fps_};
}

}  // namespace corsa::sensors::detail
