#pragma once
/// @file png_writer.hpp
/// Writing images (polar, Cartesian, overlays) as PNG files.

#include <string>

#include <opencv2/core.hpp>

namespace sonarmap {

/// Writes `image` as a PNG through cv::imwrite, atomically: it is encoded to a temporary file
/// beside `path` (same folder, name `.<file name>.tmp-<random>.png`), which is then renamed onto
/// `path` with std::filesystem::rename. A failed call leaves no partial PNG and no temporary file;
/// an existing file at `path` is only replaced by a complete one.
///
/// @param path   destination file; its folder must exist. Any extension is kept as given.
/// @param image  CV_8U or CV_16U, 1, 3 or 4 channels (what PNG stores), not empty.
/// @throws FileError  when the image is empty or of a type PNG cannot store, or when encoding,
///   writing or renaming fails (the message names `path`).
void writePng(const std::string& path, const cv::Mat& image);

}  // namespace sonarmap
