// _images: reads the image files of datasets into numpy arrays (OpenCV's codecs only, so that
// reading a dataset loads neither the renderer nor Embree). PNG keeps its bit depth (8-bit RGB
// as R G B, 16-bit grey as uint16); OpenEXR depth is float32.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"

namespace {
namespace py = pybind11;

// OpenCV keeps colour as B G R (A): the copy swaps it to R G B (A).
template <typename T>
py::array copy_of(const cv::Mat& image) {
  const int channels = image.channels();
  std::vector<py::ssize_t> shape{image.rows, image.cols};
  if (channels > 1) shape.push_back(channels);
  py::array_t<T> out(shape);
  T* data = out.mutable_data();
  const size_t row_values = static_cast<size_t>(image.cols) * static_cast<size_t>(channels);
  for (int r = 0; r < image.rows; ++r) {
    const T* row = image.ptr<T>(r);
    T* to = data + static_cast<size_t>(r) * row_values;
    if (channels < 3) {
      std::memcpy(to, row, row_values * sizeof(T));
      continue;
    }
    for (size_t i = 0; i < row_values; i += static_cast<size_t>(channels)) {
      to[i] = row[i + 2];
      to[i + 1] = row[i + 1];
      to[i + 2] = row[i];
      if (channels == 4) to[i + 3] = row[i + 3];
    }
  }
  return out;
}

py::array read_image(const std::filesystem::path& path) {
  cv::Mat image;
  {
    py::gil_scoped_release nogil;
    image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  }
  if (image.empty()) {
    throw corsa::InputError(
        corsa::make_error(path.string(), 0, "cannot read the image (missing or not an image)"));
  }
  switch (image.depth()) {
    case CV_8U:
      return copy_of<uint8_t>(image);
    case CV_16U:
      return copy_of<uint16_t>(image);
    case CV_32F:
      return copy_of<float>(image);
    default:
      throw corsa::InputError(corsa::make_error(path.string(), 0, "unexpected image depth"));
  }
}

}  // namespace

PYBIND11_MODULE(_images, module) {
  // OpenCV reads OPENCV_IO_ENABLE_OPENEXR once, at its first EXR use: set before any (datasets
  // hold depth as EXR; see sensors/writers.h).
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 1);
  module.doc() = "Image files of Corsa datasets as numpy arrays (use corsa.Dataset).";
  module.def("read", &read_image, py::arg("path"),
             "The image at `path` as a numpy array: uint8 (H, W, 3) RGB, uint8/uint16 (H, W) "
             "grey, float32 (H, W) EXR.");
}
