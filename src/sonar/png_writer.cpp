/// @file png_writer.cpp
/// PNG encoding through OpenCV, written with the io layer's atomic files.

#include "sonarmap/sonar/png_writer.hpp"

#include <opencv2/imgcodecs.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

bool isPngStorable(const cv::Mat& image) {
  const int depth = image.depth();
  const int channels = image.channels();
  return (depth == CV_8U || depth == CV_16U) && (channels == 1 || channels == 3 || channels == 4);
}

}  // namespace

std::vector<unsigned char> encodePng(const cv::Mat& image) {
  if (image.empty()) throw FileError("PNG encoding: the image is empty");
  if (!isPngStorable(image)) throw FileError("PNG encoding: PNG stores CV_8U/CV_16U with 1, 3 or 4 channels");
  std::vector<unsigned char> bytes;
  try {
    if (!cv::imencode(".png", image, bytes)) throw FileError("PNG encoding: cv::imencode failed");
  } catch (const cv::Exception& e) {
    throw FileError(std::string("PNG encoding: cv::imencode failed: ") + e.what());
  }
  return bytes;
}

void writePng(const std::string& path, const cv::Mat& image) {
  const std::vector<unsigned char> bytes = encodePng(image);
  writeBytesAtomically(path, bytes);
}

}  // namespace sonarmap
