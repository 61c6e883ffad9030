#include "corsa/sensors/preview.h"

#include <catch2/catch.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/sensors/writers.h"
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
