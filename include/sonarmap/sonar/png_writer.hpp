#pragma once
/// @file png_writer.hpp
/// Encoding and writing images (polar, Cartesian, map slices) as PNG.

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace sonarmap {

/// Encodes `image` as PNG bytes with libpng (colour images as OpenCV keeps them: B, G, R, A).
/// @param image  CV_8U or CV_16U, 1, 3 or 4 channels (what PNG stores), not empty.
/// @throws FileError when the image is empty, of a type PNG cannot store, or encoding fails.
std::vector<unsigned char> encodePng(const cv::Mat& image);

/// Writes `image` as a PNG file atomically (temporary file beside `path`, then rename): a failed
/// call leaves no partial PNG and an existing file untouched.
/// @throws FileError as encodePng, or when the file cannot be written (its folder must exist).
void writePng(const std::string& path, const cv::Mat& image);

}  // namespace sonarmap
