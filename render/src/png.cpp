#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "corsa/core/atomic_file.h"
#include "corsa/render/map_render.h"

namespace corsa::render {

std::string encode_png(const MapPicture& picture) {
  const cv::Mat rgb(picture.height, picture.width, CV_8UC3,
                    const_cast<uint8_t*>(picture.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<uchar> bytes;
  cv::imencode(".png", bgr, bytes, {cv::IMWRITE_PNG_COMPRESSION, 6});
  return std::string(bytes.begin(), bytes.end());
}

void write_png(const MapPicture& picture, const std::filesystem::path& path) {
  write_file_atomic(path, encode_png(picture), true);
}

}  // namespace corsa::render
