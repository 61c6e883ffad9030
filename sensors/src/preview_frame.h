#pragma once

// One frame of the preview video (private; preview.cpp and preview_stream.cpp compose it the same
// way, from the dataset's files or from the frames in memory, so both give the same pixels).

#include <opencv2/core.hpp>

namespace corsa::sensors::detail {

/// The preview video's frame height (pixels); the camera and the bird's-eye view are scaled to it.
inline constexpr int kPreviewHeight = 720;

/// `image` scaled to `height` rows (area averaging), or the same pixels when it has them.
cv::Mat fit_height(const cv::Mat& image, int height);

/// The video's frame size for a camera `camera_cols` wide at kPreviewHeight rows, with a
/// bird's-eye view beside it or not: even sizes (H.264 needs them).
cv::Size preview_video_size(int camera_cols, bool with_birds_eye);

/// The camera frame (8-bit BGR, any size), stamped with its `time` (s), beside `birds_eye` (8-bit
/// BGR; empty: black) on a black frame of `size`.
cv::Mat compose_preview_frame(const cv::Mat& camera, double time, const cv::Mat& birds_eye,
                              cv::Size size);

}  // namespace corsa::sensors::detail
