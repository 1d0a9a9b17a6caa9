#pragma once
/// @file byte_io.hpp
/// Private to the library (src/): little-endian reading with bounds checks and little-endian
/// writing, for the binary OctoMap formats (`.graph`, `.ot`) and the sonars' wire formats. Every
/// failed read of a ByteCursor throws FileError naming the source, the byte offset and what was
/// expected there.

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <span>
#include <string>
#include <string_view>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {

/// The little-endian 16-bit number at `bytes[at]`, `bytes[at + 1]` (the caller has checked that
/// both are there).
inline std::uint16_t u16At(std::span<const unsigned char> bytes, std::size_t at) {
  return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
}

/// The little-endian 32- and 64-bit numbers starting at `bytes` (the caller has checked that they
/// are there): one unaligned load on a little-endian host, the bytes reversed on a big-endian one.
inline std::uint32_t u32At(const unsigned char* bytes) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes, sizeof value);
  if constexpr (std::endian::native == std::endian::big) value = __builtin_bswap32(value);
  return value;
}
inline std::uint64_t u64At(const unsigned char* bytes) {
  std::uint64_t value = 0;
  std::memcpy(&value, bytes, sizeof value);
  if constexpr (std::endian::native == std::endian::big) value = __builtin_bswap64(value);
  return value;
}

/// Sequential reader over bytes already in memory. Offsets in messages are `base + position`, so
/// a reader over the data part of a file can report file offsets.
class ByteCursor {
 public:
  /// @param label word placed before offsets in messages ("byte", or "data byte" when the base
  ///        is unknown).
  ByteCursor(std::span<const unsigned char> data, const std::string& source, std::size_t base = 0,
             std::string label = "byte")
      : data_(data), source_(source), base_(base), label_(std::move(label)) {}

  /// Offset of the next byte, as reported in messages.
  std::size_t offset() const { return base_ + position_; }
  std::size_t remaining() const { return data_.size() - position_; }

  /// Throws FileError at offset `at` (as reported) with `message`.
  [[noreturn]] void failAt(std::size_t at, const std::string& message) const {
    throw FileError(source_ + ": " + label_ + " " + std::to_string(at) + ": " + message);
  }
  [[noreturn]] void fail(const std::string& message) const { failAt(offset(), message); }

  /// Throws unless `bytes` more bytes are left. @param what the field expected there.
  void require(std::size_t bytes, std::string_view what) const {
    if (bytes > remaining()) {
      fail("file ends, expected " + std::string(what) + " (" + std::to_string(bytes) + " bytes, " + std::to_string(remaining()) +
           " left)");
    }
  }

  std::uint8_t u8(std::string_view what) {
    require(1, what);
    return data_[position_++];
  }
  std::uint16_t u16(std::string_view what) {
    require(2, what);
    const std::uint16_t value = u16At(data_, position_);
    position_ += 2;
    return value;
  }
  std::uint32_t u32(std::string_view what) {
    require(4, what);
    const std::uint32_t value = u32At(data_.data() + position_);
    position_ += 4;
    return value;
  }
  std::int32_t i32(std::string_view what) { return static_cast<std::int32_t>(u32(what)); }
  std::uint64_t u64(std::string_view what) {
    require(8, what);
    const std::uint64_t value = u64At(data_.data() + position_);
    position_ += 8;
    return value;
  }

  double f64(std::string_view what) { return std::bit_cast<double>(u64(what)); }

  /// The next `bytes` bytes, stepped over. @throws FileError as require().
  std::span<const unsigned char> take(std::size_t bytes, std::string_view what) {
    require(bytes, what);
    const std::span<const unsigned char> taken = data_.subspan(position_, bytes);
    position_ += bytes;
    return taken;
  }

  /// A float32 that must be finite (NaN and ±inf throw, at the value's offset).
  float finiteF32(std::string_view what) {
    const float value = std::bit_cast<float>(u32(what));
    if (!std::isfinite(value)) failAt(offset() - 4, std::string(what) + " is " + std::to_string(value) + ", expected a finite number");
    return value;
  }
  /// A float64 that must be finite (NaN and ±inf throw, at the value's offset).
  double finiteF64(std::string_view what) {
    const double value = std::bit_cast<double>(u64(what));
    if (!std::isfinite(value)) failAt(offset() - 8, std::string(what) + " is " + std::to_string(value) + ", expected a finite number");
    return value;
  }

 private:
  std::span<const unsigned char> data_;
  const std::string& source_;
  std::size_t base_;
  std::string label_;
  std::size_t position_ = 0;
};

inline void putU32(std::string& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFU));
}
inline void putI32(std::string& out, std::int32_t value) { putU32(out, static_cast<std::uint32_t>(value)); }
inline void putF32(std::string& out, float value) { putU32(out, std::bit_cast<std::uint32_t>(value)); }
inline void putF64(std::string& out, double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xFFU));
}

}  // namespace sonarmap::detail
