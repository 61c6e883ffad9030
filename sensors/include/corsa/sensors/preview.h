#pragma once

// A quick look at a dataset (`corsa run --rig ... --preview`, scripts/demo):
//   DIR/preview/contact_sheet.png   up to 12 camera frames evenly spread over the run, 4 across,
//                                   each stamped with its time
//   DIR/preview/camera_birds_eye.mp4  the camera beside the bird's-eye view, at the camera rate
// The first RGB camera and the first bird's-eye camera of the rig are used (the video shows the
// camera alone without a bird's-eye camera). The video is H.264 ("avc1") from libx264 through
// FFmpeg's libraries at a fast preset (sensors/src/h264_writer.h) when FFmpeg has libx264; else
// OpenCV's videoio writes the first it can of H.264, MPEG-4 part 2 ("mp4v") or Motion JPEG in
// camera_birds_eye.avi, and the summary says which. The contact sheet is deterministic; the H.264
// video is the same bytes from run to run with the same FFmpeg and libx264, but depends on their
// versions and is not part of the byte-identical dataset.

#include <filesystem>
#include <functional>
#include <string>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/rig.h"

namespace corsa::sensors {

struct PreviewReport {
  std::filesystem::path contact_sheet;  ///< empty when the rig has no RGB camera frames
  std::filesystem::path video;          ///< empty when no encoder could be opened
  std::string codec;                    ///< "avc1", "mp4v", "MJPG" or empty
  int frames = 0;                       ///< video frames
  std::string summary;                  ///< one line for people
};

/// Called with (video frames encoded, frames in all) while the video is written.
using PreviewProgress = std::function<void(int done, int total)>;

/// A preview video encoded while the dataset was written (DatasetWriter::stream_preview), from
/// the frames in memory.
struct StreamedVideo {
  std::filesystem::path file;  ///< H.264 in MP4, under a temporary name in DIR/preview
  int width = 0;               ///< pixels
  int height = 0;
  int frames = 0;
  double fps = 0.0;  ///< frames a second it was opened with
};

/// Reads the dataset's frames.csv and images and writes the preview files. Throws InputError
/// when the dataset cannot be read. With `streamed`, its file becomes the video when it has the
/// frames, size and rate that encoding the dataset's images would give (the same bytes); else
/// it is removed and the images are encoded as without it.
PreviewReport write_preview(const std::filesystem::path& dataset, const SensorRig& rig,
                            Diagnostics& diagnostics, const PreviewProgress& progress = {},
                            const StreamedVideo* streamed = nullptr);

}  // namespace corsa::sensors
