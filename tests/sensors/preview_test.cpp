#include "corsa/sensors/preview.h"

#include <xmmintrin.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <opencv2/videoio.hpp>
#include <optional>
#include <string>
#include <thread>

#include "corsa/core/atomic_file.h"
#include "corsa/sensors/writers.h"
#include "preview_stream.h"
#include "temp_dir.h"

using namespace corsa::sensors;
namespace fs = std::filesystem;

namespace {

// A dataset of `frames` captures at 10 Hz of a small RGB camera and a bird's-eye view, each
// frame one flat colour that brightens with time (so the video's frames can be told apart).
SensorRig write_small_dataset(const fs::path& dir, int frames) {
  SensorRig rig;
  SensorSpec camera;
  camera.name = "cam";
  camera.kind = SensorKind::kRgbCamera;
  camera.rate_hz = 10.0;
  SensorSpec top;
  top.name = "top";
  top.kind = SensorKind::kBirdsEyeCamera;
  rig.sensors = {camera, top};
  std::string index = "capture,tick,time,sensor,frame,file,overlap\n";
  for (int i = 0; i < frames; ++i) {
    const std::string name = std::string(6 - std::to_string(i).size(), '0') + std::to_string(i);
    const std::vector<uint8_t> cam_pixels(64 * 36 * 3, static_cast<uint8_t>(40 + 10 * i));
    const std::vector<uint8_t> top_pixels(36 * 36 * 3, static_cast<uint8_t>(200 - 10 * i));
    fs::create_directories(dir / "cam");
    fs::create_directories(dir / "top");
    write_png_rgb8(dir / "cam" / (name + ".png"), 64, 36, cam_pixels);
    write_png_rgb8(dir / "top" / (name + ".png"), 36, 36, top_pixels);
    const std::string tick = std::to_string(10 * i);
    const std::string time = std::to_string(0.1 * i);
    index += std::to_string(i) + "," + tick + "," + time + ",cam," + std::to_string(i) + ",cam/" +
             name + ".png,0\n";
    index += std::to_string(i) + "," + tick + "," + time + ",top," + std::to_string(i) + ",top/" +
             name + ".png,0\n";
  }
  corsa::write_file_atomic(dir / "frames.csv", index);
  return rig;
}

// Capture i of write_small_dataset() as the sensor system hands it to the dataset writer.
std::vector<SensorFrame> small_capture(int i) {
  SensorFrame cam;
  cam.sensor = "cam";
  cam.kind = SensorKind::kRgbCamera;
  cam.frame = i;
  cam.tick = 10 * i;
  cam.time = std::stod(std::to_string(0.1 * i));  // as frames.csv above gives it
  cam.camera.width = 64;
  cam.camera.height = 36;
  cam.camera.rgb.assign(64 * 36 * 3, static_cast<uint8_t>(40 + 10 * i));
  SensorFrame top = cam;
  top.sensor = "top";
  top.kind = SensorKind::kBirdsEyeCamera;
  top.camera = {};
  top.birds_eye.width = 36;
  top.birds_eye.height = 36;
  top.birds_eye.rgb.assign(36 * 36 * 3, static_cast<uint8_t>(200 - 10 * i));
  return {cam, top};
}

}  // namespace

TEST_CASE("the preview video is H.264 with every frame, the same bytes from run to run",
          "[sensors][preview]") {
  corsa::test::TempDir dir;
  constexpr int kFrames = 14;
  const SensorRig rig = write_small_dataset(dir.path() / "a", kFrames);
  write_small_dataset(dir.path() / "b", kFrames);
  corsa::Diagnostics diagnostics;
  const PreviewReport a = write_preview(dir.path() / "a", rig, diagnostics);
  const PreviewReport b = write_preview(dir.path() / "b", rig, diagnostics);
  CHECK(diagnostics.all().empty());
  REQUIRE(a.codec == "avc1");
  CHECK(a.frames == kFrames);
  CHECK(a.video == dir.path() / "a" / "preview" / "camera_birds_eye.mp4");
  CHECK_FALSE(fs::exists(dir.path() / "a" / "preview" / ".camera_birds_eye.tmp.mp4"));
  CHECK(corsa::read_file(a.video) == corsa::read_file(b.video));

  // Read back: the camera (left, scaled to 720 rows) and the bird's-eye view (right) of each
  // frame, within the encoder's loss.
  cv::VideoCapture video(a.video.string(), cv::CAP_FFMPEG);
  REQUIRE(video.isOpened());
  int read = 0;
  cv::Mat frame;
  while (video.read(frame)) {
    REQUIRE((frame.cols == 1280 + 720 && frame.rows == 720));
    const cv::Vec3b cam = frame.at<cv::Vec3b>(500, 640);
    const cv::Vec3b top = frame.at<cv::Vec3b>(500, 1280 + 360);
    INFO("frame " << read);
    CHECK(std::abs(cam[1] - (40 + 10 * read)) <= 4);
    CHECK(std::abs(top[1] - (200 - 10 * read)) <= 4);
    ++read;
  }
  CHECK(read == kFrames);
}

TEST_CASE("a preview video encoded from the captures in memory is the one encoded from the files",
          "[sensors][preview]") {
  corsa::test::TempDir dir;
  constexpr int kFrames = 14;
  const SensorRig rig = write_small_dataset(dir.path() / "files", kFrames);
  write_small_dataset(dir.path() / "stream", kFrames);
  corsa::Diagnostics diagnostics;
  const PreviewReport from_files = write_preview(dir.path() / "files", rig, diagnostics);

  detail::PreviewStream stream(rig, dir.path() / "stream");
  for (int i = 0; i < kFrames; ++i) {
    stream.add(small_capture(i));
  }
  const std::optional<StreamedVideo> streamed = stream.finish();
  REQUIRE(streamed.has_value());
  CHECK(streamed->frames == kFrames);
  CHECK(fs::exists(streamed->file));
  int progress_calls = 0;
  const PreviewReport from_stream = write_preview(
      dir.path() / "stream", rig, diagnostics, [&](int, int) { ++progress_calls; }, &*streamed);
  CHECK(diagnostics.all().empty());
  CHECK(from_stream.frames == kFrames);
  CHECK(from_stream.codec == "avc1");
  CHECK(progress_calls == 1);
  CHECK_FALSE(fs::exists(streamed->file));
  REQUIRE(fs::exists(from_stream.video));
  CHECK(corsa::read_file(from_stream.video) == corsa::read_file(from_files.video));
}

TEST_CASE("a streamed preview video that misses frames is replaced by one from the files",
          "[sensors][preview]") {
  corsa::test::TempDir dir;
  constexpr int kFrames = 6;
  const SensorRig rig = write_small_dataset(dir.path() / "files", kFrames);
  write_small_dataset(dir.path() / "stream", kFrames);
  corsa::Diagnostics diagnostics;
  const PreviewReport from_files = write_preview(dir.path() / "files", rig, diagnostics);

  detail::PreviewStream stream(rig, dir.path() / "stream");
  for (int i = 0; i + 1 < kFrames; ++i) {  // the last capture never reached the stream
    stream.add(small_capture(i));
  }
  const std::optional<StreamedVideo> streamed = stream.finish();
  REQUIRE(streamed.has_value());
  CHECK(streamed->frames == kFrames - 1);
  const PreviewReport report =
      write_preview(dir.path() / "stream", rig, diagnostics, {}, &*streamed);
  CHECK(report.frames == kFrames);
  CHECK_FALSE(fs::exists(streamed->file));
  CHECK(corsa::read_file(report.video) == corsa::read_file(from_files.video));
}

TEST_CASE("a preview stream that is not finished leaves no file", "[sensors][preview]") {
  corsa::test::TempDir dir;
  const SensorRig rig = write_small_dataset(dir.path(), 3);
  fs::path file;
  {
    detail::PreviewStream stream(rig, dir.path());
    for (int i = 0; i < 3; ++i) {
      stream.add(small_capture(i));
    }
    file = dir.path() / "preview" / ".camera_birds_eye.stream.mp4";
    // The encoder opens its file with the first frame, on its own thread.
    for (int wait = 0; wait < 200 && !fs::exists(file); ++wait) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    REQUIRE(fs::exists(file));
  }  // an interrupted run: destroyed without finish()
  CHECK_FALSE(fs::exists(file));
}

TEST_CASE("the preview video does not depend on the calling thread's floating-point register",
          "[sensors][preview]") {
  corsa::test::TempDir dir;
  constexpr int kFrames = 14;
  const SensorRig rig = write_small_dataset(dir.path() / "plain", kFrames);
  write_small_dataset(dir.path() / "flushed", kFrames);
  corsa::Diagnostics diagnostics;
  const PreviewReport plain = write_preview(dir.path() / "plain", rig, diagnostics);
  // Flush-to-zero and denormals-are-zero, as oneTBB's workers have run with.
  constexpr unsigned kFlushBits = 0x8040;
  PreviewReport flushed;
  unsigned after = 0;
  std::thread caller([&] {
    _mm_setcsr(_mm_getcsr() | kFlushBits);
    flushed = write_preview(dir.path() / "flushed", rig, diagnostics);
    after = _mm_getcsr();
  });
  caller.join();
  CHECK(diagnostics.all().empty());
  CHECK((after & kFlushBits) == kFlushBits);  // the caller's register is put back
  REQUIRE(flushed.frames == kFrames);
  CHECK(corsa::read_file(flushed.video) == corsa::read_file(plain.video));
}
