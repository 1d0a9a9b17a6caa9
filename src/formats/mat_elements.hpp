#pragma once
/// @file mat_elements.hpp
/// Private to src/formats: the data elements of a MAT-file v5 (MathWorks, "MAT-File Format",
/// version 5, chapter 1), read one by one with every size checked against the bytes that hold
/// them; shared by the size check (mat_size_check.cpp) and the reading of a file cut short
/// (mat_cut.cpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {

// Data types and array classes of the MAT-file v5 format (tables 1-1 and 1-3).
inline constexpr std::uint32_t kMiInt8 = 1, kMiInt32 = 5, kMiUint32 = 6, kMiMatrix = 14, kMiCompressed = 15;
inline constexpr std::uint32_t kCellClass = 1, kStructClass = 2, kObjectClass = 3, kSparseClass = 5;
inline constexpr std::size_t kMatHeaderBytes = 128;

/// A data element: its type and its content (tag excluded).
struct Element {
  std::uint32_t type = 0;
  std::span<const unsigned char> content;
  std::size_t offset = 0;  ///< of the tag, as reported in messages
};

/// Sequential reader of the data elements inside one container (the file, or an array's bytes).
class ElementReader {
 public:
  ElementReader(std::span<const unsigned char> bytes, std::size_t base, bool swap, const std::string& where)
      : bytes_(bytes), base_(base), swap_(swap), where_(where) {}

  bool atEnd() const { return position_ >= bytes_.size(); }
  /// Whether the next element runs past the bytes: a tag cut short, or a full element declaring
  /// more bytes than are left (what the end of a file cut short looks like).
  bool cutShort() const {
    if (atEnd()) return false;
    if (bytes_.size() - position_ < 8) return true;
    return (u32At(bytes_, position_) >> 16) == 0 && u32At(bytes_, position_ + 4) > bytes_.size() - position_ - 8;
  }
  std::size_t offset() const { return base_ + position_; }
  std::span<const unsigned char> rest() const { return bytes_.subspan(position_); }

  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw FileError(where_ + ": byte " + std::to_string(at) + ": " + message);
  }

  std::uint32_t u32At(std::span<const unsigned char> bytes, std::size_t at) const {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) {
      const unsigned shift = swap_ ? 8U * (3U - static_cast<unsigned>(i)) : 8U * static_cast<unsigned>(i);
      value |= static_cast<std::uint32_t>(bytes[at + static_cast<std::size_t>(i)]) << shift;
    }
    return value;
  }

  /// The next element: a small one (type and size in one word, content in the next 4 bytes) or a
  /// full one (8-byte tag, content padded to 8 bytes, except compressed content).
  Element next() {
    const std::size_t at = offset();
    if (bytes_.size() - position_ < 8) fail(at, "expected an 8-byte data element tag, " + left());
    const std::uint32_t word = u32At(bytes_, position_);
    if ((word >> 16) != 0) {  // small data element format
      const std::size_t size = word >> 16;
      if (size > 4) fail(at, "small data element declares " + std::to_string(size) + " bytes, at most 4 fit");
      Element e{word & 0xFFFFU, bytes_.subspan(position_ + 4, size), at};
      position_ += 8;
      return e;
    }
    const std::size_t size = u32At(bytes_, position_ + 4);
    position_ += 8;
    if (size > bytes_.size() - position_) {
      fail(at, "data element declares " + std::to_string(size) + " bytes, " + left());
    }
    Element e{word, bytes_.subspan(position_, size), at};
    const std::size_t padded = word == kMiCompressed ? size : (size + 7) / 8 * 8;
    position_ += std::min(padded, bytes_.size() - position_);
    return e;
  }

  /// The next element, which must be of `type`.
  Element expect(std::uint32_t type, const char* what) {
    const std::size_t at = offset();
    const Element e = next();
    if (e.type != type) fail(at, std::string("expected ") + what + " (data type " + std::to_string(type) + "), found data type " + std::to_string(e.type));
    return e;
  }

  bool swap() const { return swap_; }
  const std::string& where() const { return where_; }

 private:
  std::string left() const { return std::to_string(bytes_.size() - position_) + " left"; }

  std::span<const unsigned char> bytes_;
  std::size_t base_;
  bool swap_;
  const std::string& where_;
  std::size_t position_ = 0;
};

/// Inflates a compressed variable's zlib stream, at most kMaxInflatedMatBytes; a stream cut short
/// gives what inflates from the bytes there.
/// @throws FileError (through `reader`) for a stream that does not inflate or inflates beyond the limit.
std::vector<unsigned char> inflateElement(const Element& compressed, const ElementReader& reader);

}  // namespace sonarmap::detail
