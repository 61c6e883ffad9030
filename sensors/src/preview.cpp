// Dataset preview: contact sheet and camera + bird's-eye video (see corsa/sensors/preview.h).

#include "corsa/sensors/preview.h"

#include <algorithm>
#include <future>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "h264_writer.h"
#include "png_codec.h"
#include "preview_frame.h"

namespace corsa::sensors {
namespace detail {
namespace {

void stamp(cv::Mat& image, const std::string& text, double scale) {
  const cv::Point at(8, static_cast<int>(24 * scale));
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.7 * scale, cv::Scalar(0, 0, 0),
              static_cast<int>(4 * scale), cv::LINE_AA);
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.7 * scale, cv::Scalar(255, 255, 255),
              static_cast<int>(std::max(1.0, 1.5 * scale)), cv::LINE_AA);
}

}  // namespace

cv::Mat fit_height(const cv::Mat& image, int height) {
  if (image.rows == height) {
    return image;  // shares the pixels: no copy
  }
  cv::Mat out;
  const int width = std::max(1, image.cols * height / std::max(1, image.rows));
  cv::resize(image, out, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  return out;
}

cv::Size preview_video_size(int camera_cols, bool with_birds_eye) {
  const int side = with_birds_eye ? kPreviewHeight : 0;
  return {(camera_cols + side + 1) / 2 * 2, kPreviewHeight};
}

cv::Mat compose_preview_frame(const cv::Mat& camera, double time, const cv::Mat& birds_eye,
                              cv::Size size) {
  cv::Mat frame(size, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::Mat cam = fit_height(camera, kPreviewHeight);
  stamp(cam, "t = " + format_fixed(time, 1) + " s", 1.0);
  cam.copyTo(frame(cv::Rect(0, 0, cam.cols, cam.rows)));
  if (!birds_eye.empty()) {
    const cv::Mat top = fit_height(birds_eye, kPreviewHeight);
    top.copyTo(frame(cv::Rect(cam.cols, 0, top.cols, top.rows)));
  }
  return frame;
}

}  // namespace detail

namespace {

namespace fs = std::filesystem;

struct Shot {
  int64_t tick = 0;
  double time = 0.0;
  std::string file;
};

// The image file of each frame of `sensor` (the .png named like the frame), in capture order.
std::vector<Shot> shots_of(const std::string& index, const std::string& sensor) {
  std::vector<Shot> out;
  std::istringstream in(index);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const std::vector<std::string_view> f = split(line, ',');
    if (f.size() < 6 || f[3] != sensor) {
      continue;
    }
    const std::string file(f[5]);
    const std::string name = fs::path(file).filename().string();
    if (name.size() != 10 || !name.ends_with(".png")) {
      continue;  // 000000.png only, not _color.png or labels
    }
    out.push_back({parse_int(f[1]).value_or(0), parse_double(f[2]).value_or(0.0), file});
  }
  return out;
}

// The dataset's camera images are 8-bit RGB PNGs, decoded here with libdeflate (about half the
// CPU of OpenCV's libpng + zlib); anything else is read by OpenCV.
cv::Mat read_rgb(const fs::path& path) {
  std::error_code error;
  if (path.extension() == ".png" && fs::is_regular_file(path, error)) {
    if (std::optional<cv::Mat> decoded = detail::decode_png_rgb8(read_file(path))) {
      return *std::move(decoded);
    }
  }
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty()) {
    throw InputError(make_error(path.string(), 0, "cannot read the image for the preview"));
  }
  return image;
}

fs::path write_contact_sheet(const fs::path& dataset, const std::vector<Shot>& shots) {
  constexpr int kColumns = 4;
  constexpr size_t kMax = 12;
  constexpr int kTileWidth = 400;
  const size_t n = std::min(kMax, shots.size());
  std::vector<cv::Mat> tiles;
  for (size_t i = 0; i < n; ++i) {
    const size_t pick = n == 1 ? 0 : i * (shots.size() - 1) / (n - 1);
    cv::Mat image = read_rgb(dataset / shots[pick].file);
    cv::Mat tile;
    const int height = image.rows * kTileWidth / std::max(1, image.cols);
    cv::resize(image, tile, cv::Size(kTileWidth, height), 0, 0, cv::INTER_AREA);
    detail::stamp(tile, "t = " + format_fixed(shots[pick].time, 1) + " s", 0.8);
    tiles.push_back(tile);
  }
  const int rows = static_cast<int>((n + kColumns - 1) / kColumns);
  const int tile_h = tiles.front().rows;
  cv::Mat sheet(rows * tile_h + (rows + 1) * 4, kColumns * kTileWidth + (kColumns + 1) * 4, CV_8UC3,
                cv::Scalar(40, 40, 40));
  for (size_t i = 0; i < tiles.size(); ++i) {
    const int r = static_cast<int>(i) / kColumns;
    const int c = static_cast<int>(i) % kColumns;
    tiles[i].copyTo(
        sheet(cv::Rect(4 + c * (kTileWidth + 4), 4 + r * (tile_h + 4), kTileWidth, tiles[i].rows)));
  }
  std::vector<uchar> png;
  cv::imencode(".png", sheet, png);
  const fs::path path = dataset / "preview" / "contact_sheet.png";
  write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()),
                    true);
  return path;
}

// Opens a writer with the first codec the OpenCV build offers; the file is written under a
// temporary name and renamed when complete.
bool open_video(cv::VideoWriter& writer, const fs::path& dir, cv::Size size, double fps,
                fs::path& final_path, fs::path& temporary, std::string& codec) {
  struct Choice {
    const char* fourcc;
    const char* extension;
  };
  for (const Choice choice :
       {Choice{"avc1", ".mp4"}, Choice{"mp4v", ".mp4"}, Choice{"MJPG", ".avi"}}) {
    final_path = dir / (std::string("camera_birds_eye") + choice.extension);
    temporary = dir / (std::string(".camera_birds_eye.tmp") + choice.extension);
    const int fourcc = cv::VideoWriter::fourcc(choice.fourcc[0], choice.fourcc[1], choice.fourcc[2],
                                               choice.fourcc[3]);
    if (writer.open(temporary.string(), cv::CAP_FFMPEG, fourcc, fps, size, true) ||
        writer.open(temporary.string(), fourcc, fps, size, true)) {
      codec = choice.fourcc;
      return true;
    }
    std::error_code ignored;
    fs::remove(temporary, ignored);
  }
  return false;
}

double frame_rate(const std::vector<Shot>& shots) {
  if (shots.size() < 2 || shots.back().time <= shots.front().time) {
    return 10.0;
  }
  return static_cast<double>(shots.size() - 1) / (shots.back().time - shots.front().time);
}

}  // namespace

PreviewReport write_preview(const fs::path& dataset, const SensorRig& rig, Diagnostics& diagnostics,
                            const PreviewProgress& progress, const StreamedVideo* streamed) {
  PreviewReport report;
  const SensorSpec* camera = nullptr;
  const SensorSpec* birds_eye = nullptr;
  for (const SensorSpec& s : rig.sensors) {
    if (camera == nullptr && s.kind == SensorKind::kRgbCamera) {
      camera = &s;
    }
    if (birds_eye == nullptr && s.kind == SensorKind::kBirdsEyeCamera) {
      birds_eye = &s;
    }
  }
  const std::string index = read_file(dataset / "frames.csv");
  const std::vector<Shot> shots = camera ? shots_of(index, camera->name) : std::vector<Shot>{};
  if (shots.empty()) {
    report.summary = "preview: no RGB camera frames in " + dataset.string() + "; nothing written";
    return report;
  }
  std::error_code error;
  fs::create_directories(dataset / "preview", error);
  report.contact_sheet = write_contact_sheet(dataset, shots);

  std::map<int64_t, std::string> top;  // bird's-eye frame by tick
  if (birds_eye != nullptr) {
    for (const Shot& s : shots_of(index, birds_eye->name)) {
      top[s.tick] = s.file;
    }
  }
  const cv::Mat first =
      detail::fit_height(read_rgb(dataset / shots.front().file), detail::kPreviewHeight);
  const cv::Size size = detail::preview_video_size(first.cols, !top.empty());
  const double fps = frame_rate(shots);
  if (streamed != nullptr) {
    // Encoded during the run from the frames in memory: the same frames, size and rate give the
    // same file as encoding the dataset's images now.
    const fs::path video = dataset / "preview" / "camera_birds_eye.mp4";
    const bool same = streamed->frames == static_cast<int>(shots.size()) &&
                      streamed->width == size.width && streamed->height == size.height &&
                      detail::H264Writer::same_frame_rate(streamed->fps, fps);
    if (same) {
      fs::rename(streamed->file, video, error);
    }
    if (same && !error) {
      report.video = video;
      report.codec = "avc1";
      report.frames = streamed->frames;
      if (progress) {
        progress(report.frames, report.frames);
      }
      report.summary = "preview: " + report.contact_sheet.string() + ", " + report.video.string() +
                       " (" + std::to_string(report.frames) + " frames, avc1, H.264)";
      return report;
    }
    std::error_code ignored;
    fs::remove(streamed->file, ignored);
  }
  // H.264 through libx264 directly when FFmpeg has it; otherwise OpenCV's writers.
  const fs::path h264_temporary = dataset / "preview" / ".camera_birds_eye.tmp.mp4";
  std::unique_ptr<detail::H264Writer> h264 = detail::H264Writer::open(h264_temporary, size, fps);
  cv::VideoWriter writer;
  fs::path temporary;
  if (h264 != nullptr) {
    report.video = dataset / "preview" / "camera_birds_eye.mp4";
    report.codec = "avc1";
    temporary = h264_temporary;
  } else if (!open_video(writer, dataset / "preview", size, fps, report.video, temporary,
                         report.codec)) {
    diagnostics.add(make_warning("", 0,
                                 "preview: this OpenCV build cannot encode video (no avc1, mp4v "
                                 "or MJPG writer); only the contact sheet was written"));
    report.video.clear();
  }
  if (!report.video.empty()) {
    // The camera frame, stamped, beside the latest bird's-eye view at or before its tick (black
    // before the first).
    const auto compose = [&](size_t i) {
      const auto found = top.upper_bound(shots[i].tick);
      const cv::Mat latest_top =
          found != top.begin() ? read_rgb(dataset / std::prev(found)->second) : cv::Mat();
      return detail::compose_preview_frame(read_rgb(dataset / shots[i].file), shots[i].time,
                                           latest_top, size);
    };
    // The next frame is read and composed on a thread of its own while this one is encoded on
    // the caller's thread: the encoder sees the same frames in the same order, so the same bytes.
    std::future<cv::Mat> next = std::async(std::launch::async, compose, size_t{0});
    for (size_t i = 0; i < shots.size(); ++i) {
      const cv::Mat frame = next.get();
      if (i + 1 < shots.size()) {
        next = std::async(std::launch::async, compose, i + 1);
      }
      if (h264 != nullptr) {
        h264->write(frame);
      } else {
        writer.write(frame);
      }
      ++report.frames;
      if (progress) {
        progress(report.frames, static_cast<int>(shots.size()));
      }
    }
    if (h264 != nullptr) {
      h264->finish();
      h264.reset();
    } else {
      writer.release();
    }
    fs::rename(temporary, report.video, error);
    if (error) {
      throw InputError(make_error(report.video.string(), 0, "cannot write: " + error.message()));
    }
  }
  report.summary = "preview: " + report.contact_sheet.string();
  if (!report.video.empty()) {
    report.summary += ", " + report.video.string() + " (" + std::to_string(report.frames) +
                      " frames, " + report.codec +
                      (report.codec == "avc1"   ? ", H.264)"
                       : report.codec == "mp4v" ? ", MPEG-4 part 2: this OpenCV has no H.264)"
                                                : ": this OpenCV has no MP4 encoder)");
  }
  return report;
}

}  // namespace corsa::sensors
