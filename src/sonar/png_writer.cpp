/// @file png_writer.cpp
/// writePng: atomic PNG writing through cv::imwrite (see png_writer.hpp).

#include "sonarmap/sonar/png_writer.hpp"

#include <filesystem>
#include <random>
#include <string>
#include <system_error>

#include <opencv2/imgcodecs.hpp>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void throwWriteError(const std::string& path, const std::string& what) {
  throw FileError("writePng: '" + path + "': " + what);
}

/// A fresh name beside `target`, ending in .png so that cv::imwrite picks the PNG encoder.
fs::path temporaryBeside(const fs::path& target) {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  std::string name = ".";  // appended piecewise: GCC 12 warns falsely on "." + std::string
  name += target.filename().string();
  name += ".tmp-";
  name += std::to_string(random());
  name += ".png";
  return target.parent_path() / name;
}

bool isPngStorable(const cv::Mat& image) {
  const int depth = image.depth();
  const int channels = image.channels();
  return (depth == CV_8U || depth == CV_16U) && (channels == 1 || channels == 3 || channels == 4);
}

/// Encodes `image` into `file`; returns an error text, empty on success.
std::string encodeTo(const fs::path& file, const cv::Mat& image) {
  try {
    if (cv::imwrite(file.string(), image)) return {};
    return "cv::imwrite failed";
  } catch (const cv::Exception& e) {
    return std::string("cv::imwrite failed: ") + e.what();
  }
}

}  // namespace

void writePng(const std::string& path, const cv::Mat& image) {
  if (image.empty()) throwWriteError(path, "the image is empty");
  if (!isPngStorable(image)) throwWriteError(path, "PNG stores CV_8U/CV_16U with 1, 3 or 4 channels");
  const fs::path target(path);
  if (target.filename().empty()) throwWriteError(path, "not a file name");
  const fs::path temporary = temporaryBeside(target);
  std::error_code ec;
  if (const std::string error = encodeTo(temporary, image); !error.empty()) {
    fs::remove(temporary, ec);
    throwWriteError(path, error + " (writing the temporary " + temporary.string() + ")");
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throwWriteError(path, "cannot rename the temporary file onto it: " + ec.message());
  }
}

}  // namespace sonarmap
