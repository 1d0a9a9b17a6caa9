/// @file text_input.cpp
/// openTextInput (text_input.hpp): a std::streambuf that inflates a gzip file chunk by chunk.

#include "sonarmap/io/text_input.hpp"

#include <zlib.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kChunkBytes = 1 << 16;

bool namedGz(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".gz" || extension == ".GZ";
}

/// Inflates the gzip members of `file` into a buffer the stream reads from.
class GzipBuffer : public std::streambuf {
 public:
  GzipBuffer(std::ifstream file, std::string path) : file_(std::move(file)), path_(std::move(path)) {
    // 15 + 16: a gzip wrapper (not zlib's, not raw deflate), the largest window.
    if (inflateInit2(&stream_, 15 + 16) != Z_OK) throw FileError("'" + path_ + "': zlib cannot start inflating");
  }
  ~GzipBuffer() override { inflateEnd(&stream_); }
  GzipBuffer(const GzipBuffer&) = delete;
  GzipBuffer& operator=(const GzipBuffer&) = delete;

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    while (true) {
      if (stream_.avail_in == 0 && !refill()) {
        if (in_member_) throw FileError("'" + path_ + "': truncated gzip data: the file ends inside a compressed member");
        return traits_type::eof();
      }
      if (!in_member_) {  // the next member starts here (or only padding follows the last)
        in_member_ = true;
        if (inflateReset(&stream_) != Z_OK) throw FileError("'" + path_ + "': zlib cannot restart inflating");
      }
      stream_.next_out = reinterpret_cast<Bytef*>(out_.data());
      stream_.avail_out = static_cast<uInt>(out_.size());
      const int status = inflate(&stream_, Z_NO_FLUSH);
      if (status == Z_STREAM_END) {
        in_member_ = false;
      } else if (status != Z_OK && status != Z_BUF_ERROR) {
        const std::uint64_t at = consumed_ - stream_.avail_in;
        throw FileError("'" + path_ + "': not valid gzip data (" + (stream_.msg ? stream_.msg : "zlib error " + std::to_string(status)) +
                        ") at compressed byte " + std::to_string(at));
      }
      const std::size_t produced = out_.size() - stream_.avail_out;
      if (produced > 0) {
        setg(out_.data(), out_.data(), out_.data() + produced);
        return traits_type::to_int_type(*gptr());
      }
    }
  }

 private:
  /// Reads the next chunk of compressed bytes; false at the end of the file.
  bool refill() {
    file_.read(in_.data(), static_cast<std::streamsize>(in_.size()));
    const std::streamsize got = file_.gcount();
    if (got <= 0) {
      if (file_.bad()) throw FileError("'" + path_ + "': read error");
      return false;
    }
    stream_.next_in = reinterpret_cast<Bytef*>(in_.data());
    stream_.avail_in = static_cast<uInt>(got);
    consumed_ += static_cast<std::uint64_t>(got);
    return true;
  }

  std::ifstream file_;
  std::string path_;
  z_stream stream_{};
  std::array<char, kChunkBytes> in_{};
  std::array<char, kChunkBytes> out_{};
  std::uint64_t consumed_ = 0;  ///< compressed bytes read from the file so far
  bool in_member_ = false;      ///< inside a gzip member that has not ended
};

/// An istream that owns its buffer.
class GzipStream : public std::istream {
 public:
  GzipStream(std::ifstream file, const std::string& path) : std::istream(nullptr), buffer_(std::move(file), path) {
    rdbuf(&buffer_);
    exceptions(std::ios::badbit);  // the buffer's FileError reaches the reader
  }

 private:
  GzipBuffer buffer_;
};

}  // namespace

std::unique_ptr<std::istream> openTextInput(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw FileError("cannot open '" + path + "' for reading");
  std::array<unsigned char, 2> magic{};
  file.read(reinterpret_cast<char*>(magic.data()), 2);
  const bool gzip = file.gcount() == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
  if (!gzip && namedGz(path)) throw FileError("'" + path + "': named .gz but not gzip-compressed (no gzip magic bytes 1f 8b)");
  if (gzip) {
    file.clear();
    file.seekg(0);
    return std::make_unique<GzipStream>(std::move(file), path);
  }
  auto text = std::make_unique<std::ifstream>(path);
  if (!*text) throw FileError("cannot open '" + path + "' for reading");
  return text;
}

}  // namespace sonarmap
