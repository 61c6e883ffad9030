// corsa_look_sheet: puts camera frames side by side on one labelled contact sheet (rows are
// places, columns conditions), for docs/images/look.jpg (scripts/look-sheet makes it).
// Usage: corsa_look_sheet OUT.jpg THUMB_WIDTH COLUMN_LABELS ROW_LABELS IMAGE...
//   COLUMN_LABELS, ROW_LABELS: comma-separated; IMAGE: row by row, COLUMNS x ROWS files (a
//   missing file leaves its cell grey). The sheet is a JPEG of quality 85.

#include <iostream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    out.push_back(item);
  }
  return out;
}

void label(cv::Mat& img, const std::string& text, cv::Point at, double scale) {
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::cerr << "usage: corsa_look_sheet OUT.jpg THUMB_WIDTH COLUMN_LABELS ROW_LABELS IMAGE...\n";
    return 2;
  }
  const std::string out = argv[1];
  const int thumb_w = std::stoi(argv[2]);
  const auto columns = split(argv[3]);
  const auto rows = split(argv[4]);
  const int cols = static_cast<int>(columns.size());
  const int nrows = static_cast<int>(rows.size());
  if (argc - 5 != cols * nrows) {
    std::cerr << "corsa_look_sheet: expected " << cols * nrows << " images, got " << argc - 5
              << "\n";
    return 2;
  }
  const int thumb_h = thumb_w * 9 / 16;
  const int margin = 22;
  cv::Mat sheet(margin + nrows * thumb_h, margin + cols * thumb_w, CV_8UC3, cv::Scalar(40, 40, 40));
  for (int r = 0; r < nrows; ++r) {
    for (int c = 0; c < cols; ++c) {
      cv::Mat img = cv::imread(argv[5 + r * cols + c], cv::IMREAD_COLOR);
      cv::Mat cell = sheet(cv::Rect(margin + c * thumb_w, margin + r * thumb_h, thumb_w, thumb_h));
      if (img.empty()) {
        cell.setTo(cv::Scalar(90, 90, 90));
        continue;
      }
      cv::resize(img, cell, cell.size(), 0, 0, cv::INTER_AREA);
    }
  }
  for (int c = 0; c < cols; ++c) {
    label(sheet, columns[c], {margin + c * thumb_w + 6, 16}, 0.5);
  }
  for (int r = 0; r < nrows; ++r) {
    cv::Mat rotated;
    cv::Mat strip(margin, thumb_h, CV_8UC3, cv::Scalar(40, 40, 40));
    label(strip, rows[r], {6, 16}, 0.5);
    cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    rotated.copyTo(sheet(cv::Rect(0, margin + r * thumb_h, margin, thumb_h)));
  }
  if (!cv::imwrite(out, sheet, {cv::IMWRITE_JPEG_QUALITY, 85})) {
    std::cerr << "corsa_look_sheet: cannot write " << out << "\n";
    return 1;
  }
  return 0;
}
