/// @file png_writer.cpp
/// PNG encoding with libpng (the PNG reference library, libpng 1.6 manual, "Writing"), written with
/// the io layer's atomic files. libpng rather than OpenCV's imgcodecs: imgcodecs loads about 80
/// shared libraries (GDAL, codecs) at start-up, 60 ms and 33 MB of every `sonarmap` process.

#include "sonarmap/sonar/png_writer.hpp"

#include <png.h>

#include <csetjmp>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

bool isPngStorable(const cv::Mat& image) {
  const int depth = image.depth();
  const int channels = image.channels();
  return (depth == CV_8U || depth == CV_16U) && (channels == 1 || channels == 3 || channels == 4);
}

/// What libpng's callbacks report back: the bytes written, and its error message if any.
struct PngOutput {
  std::vector<unsigned char> bytes;
  std::string error;
};

/// libpng's write callback. An allocation failure becomes a libpng error (its longjmp), so that no
/// C++ exception crosses libpng's C frames.
void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* output = static_cast<PngOutput*>(png_get_io_ptr(png));
  bool out_of_memory = false;
  try {
    output->bytes.insert(output->bytes.end(), data, data + length);
  } catch (const std::bad_alloc&) {
    out_of_memory = true;
  }
  if (out_of_memory) png_error(png, "out of memory for the encoded image");
}

void flushNothing(png_structp /*png*/) {}

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  static_cast<PngOutput*>(png_get_error_ptr(png))->error = message;
  png_longjmp(png, 1);
}

void onPngWarning(png_structp /*png*/, png_const_charp /*message*/) {}

/// Writes `image` through `png` into `output`; false after a libpng error (its message in
/// `output`). Only trivially destructible objects live in this frame, so that libpng's longjmp
/// back to the setjmp below skips no destructor.
bool writeImage(png_structp png, png_infop info, const cv::Mat& image) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  const int channels = image.channels();
  const int color = channels == 1 ? PNG_COLOR_TYPE_GRAY : channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA;
  const int bit_depth = image.depth() == CV_16U ? 16 : 8;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.cols), static_cast<png_uint_32>(image.rows), bit_depth, color,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (channels >= 3) png_set_bgr(png);   // OpenCV keeps colours as B, G, R(, A)
  if (bit_depth == 16) png_set_swap(png);  // PNG stores 16-bit samples big-endian
  for (int r = 0; r < image.rows; ++r) png_write_row(png, const_cast<png_bytep>(image.ptr<png_byte>(r)));
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

std::vector<unsigned char> encodePng(const cv::Mat& image) {
  if (image.empty()) throw FileError("PNG encoding: the image is empty");
  if (!isPngStorable(image)) throw FileError("PNG encoding: PNG stores CV_8U/CV_16U with 1, 3 or 4 channels");
  PngOutput output;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &output, onPngError, onPngWarning);
  if (png == nullptr) throw FileError("PNG encoding: libpng could not start");
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    throw FileError("PNG encoding: libpng could not start");
  }
  png_set_write_fn(png, &output, appendBytes, flushNothing);
  const bool written = writeImage(png, info, image);
  png_destroy_write_struct(&png, &info);
  if (!written) throw FileError("PNG encoding: libpng failed: " + output.error);
  return std::move(output.bytes);
}

void writePng(const std::string& path, const cv::Mat& image) {
  const std::vector<unsigned char> bytes = encodePng(image);
  writeBytesAtomically(path, bytes);
}

}  // namespace sonarmap
