#pragma once

// A quick look at a dataset (`corsa run --rig ... --preview`, scripts/demo):
//   DIR/preview/contact_sheet.png   up to 12 camera frames evenly spread over the run, 4 across,
//                                   each stamped with its time
//   DIR/preview/camera_birds_eye.mp4  the camera beside the bird's-eye view, at the camera rate
// The first RGB camera and the first bird's-eye camera of the rig are used (the video shows the
// camera alone without a bird's-eye camera). The video is encoded with OpenCV's videoio: H.264
// ("avc1") when the FFmpeg build offers it, else MPEG-4 part 2 ("mp4v"), else Motion JPEG in
// camera_birds_eye.avi, and the summary says which. The contact sheet is deterministic; the video
// depends on the encoder and is not part of the byte-identical dataset.
// During a run the video is encoded capture by capture (PreviewRecorder, beside the rendering);
// write_preview() keeps it when it equals what encoding the finished dataset would give.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/rig.h"

namespace corsa::sensors {

struct PreviewReport {
  std::filesystem::path contact_sheet;  ///< empty when the rig has no RGB camera frames
  std::filesystem::path video;          ///< empty when no encoder could be opened
  std::string codec;                    ///< "avc1", "mp4v", "MJPG" or empty
  int frames = 0;                       ///< video frames
  bool during_run = false;  ///< the video is the one a PreviewRecorder encoded during the run
  std::string summary;      ///< one line for people
};

/// Called with (video frames encoded, frames in all) while the video is written.
using PreviewProgress = std::function<void(int done, int total)>;

/// The preview video encoded while the dataset is collected: each capture's frame is composed
/// from its files once they are in the index, on a task that runs beside the next capture's
/// rendering, so the encoder no longer runs alone after the last capture. write_preview() keeps
/// this video only when it holds exactly the frames, size and rate it would have encoded itself
/// (the same composing code, the same encoder and settings); otherwise it encodes the video from
/// the files as before. The frames are the same either way; libx264's bytes for a video longer
/// than its look-ahead depend on when the frames arrive (docs/datasets.md, Preview). Not
/// thread-safe: one caller (the dataset writer).
class PreviewRecorder {
 public:
  /// A file of a capture: the sensor's name and the file's path relative to the dataset.
  using CaptureFile = std::pair<std::string, std::filesystem::path>;

  PreviewRecorder(std::filesystem::path dataset, const SensorRig& rig);
  /// Waits for the frame being encoded; an unfinished video's temporary file is removed.
  ~PreviewRecorder();
  PreviewRecorder(const PreviewRecorder&) = delete;
  PreviewRecorder& operator=(const PreviewRecorder&) = delete;

  /// Queues one indexed capture: its tick, its time as the index writes it (`time_text`) and its
  /// files. Returns at once after the previous capture's frame is encoded. A failure (an image
  /// that cannot be read, no encoder) stops the recording; write_preview() then starts over.
  void add(int64_t tick, const std::string& time_text, const std::vector<CaptureFile>& files);

  /// Waits for the last frame. When the video holds exactly the camera frames `files` (paths as
  /// the index names them) at `fps` frames a second, with a bird's-eye column exactly when
  /// `with_top`, closes it under its final name, sets the report's video, codec and frames and
  /// returns true; otherwise removes it and returns false. Used by write_preview().
  bool finish(const std::vector<std::string>& files, double fps, bool with_top,
              PreviewReport& report);

  struct State;  ///< the writer, the frames so far and the task encoding one (preview.cpp)

 private:
  std::unique_ptr<State> state_;
};

/// Reads the dataset's frames.csv and images and writes the preview files. Throws InputError
/// when the dataset cannot be read. With `recorded` (the video encoded during the run), its video
/// is kept when it is the one this call would write, and the rest of the work is the contact sheet.
PreviewReport write_preview(const std::filesystem::path& dataset, const SensorRig& rig,
                            Diagnostics& diagnostics, const PreviewProgress& progress = {},
                            PreviewRecorder* recorded = nullptr);

}  // namespace corsa::sensors
