/// @file mat_size_check.cpp
/// checkMatSizes: a bounds-checked walk over MAT-file v5 data elements (see mat_size_check.hpp).

#include "mat_size_check.hpp"

#include "mat_elements.hpp"

#include <zlib.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr int kMaxDepth = 32;

void checkArray(const Element& matrix, bool swap, const std::string& where, int depth);

/// Product of the dimensions, or fails on a negative one; saturates at the largest size_t.
std::size_t elementCount(const ElementReader& reader, const Element& dims) {
  if (dims.content.size() % 4 != 0) reader.fail(dims.offset, "dimensions are not a whole number of int32");
  std::size_t count = 1;
  for (std::size_t i = 0; i < dims.content.size(); i += 4) {
    const auto dim = static_cast<std::int32_t>(reader.u32At(dims.content, i));
    if (dim < 0) reader.fail(dims.offset, "dimension " + std::to_string(i / 4) + " is " + std::to_string(dim) + ", expected ≥ 0");
    const auto d = static_cast<std::size_t>(dim);
    count = d != 0 && count > std::numeric_limits<std::size_t>::max() / d ? std::numeric_limits<std::size_t>::max() : count * d;
  }
  return count;
}

/// @param what the plural of what is counted ("elements", "cells"…).
void requireFits(const ElementReader& reader, std::size_t at, std::size_t count, std::size_t bytes_each, std::size_t bytes,
                 const char* what) {
  if (count > bytes / bytes_each) {
    reader.fail(at, "array declares " + std::to_string(count) + " " + what + " but holds only " + std::to_string(bytes) +
                        " bytes, at least " + std::to_string(bytes_each) + " bytes needed for each");
  }
}

/// Checks the miMATRIX elements a cell, struct or object array holds, `count` of them (anything
/// after them is checked as data subelements by checkArray).
void checkChildren(ElementReader& reader, std::size_t count, int depth) {
  for (std::size_t i = 0; i < count && !reader.atEnd(); ++i) {
    const Element child = reader.next();
    if (child.type == kMiMatrix) checkArray(child, reader.swap(), reader.where(), depth + 1);
  }
}

/// Checks one array (miMATRIX content): flags, dimensions, name, then what its class stores.
void checkArray(const Element& matrix, bool swap, const std::string& where, int depth) {
  ElementReader reader(matrix.content, matrix.offset + 8, swap, where);
  if (depth > kMaxDepth) reader.fail(matrix.offset, "arrays nested deeper than " + std::to_string(kMaxDepth) + " levels");
  // Its subelements are padded to 8 bytes, so its size is too; libmatio skips an array by that
  // size, and the walk must step exactly as libmatio does to check what libmatio will read.
  if (matrix.content.size() % 8 != 0) {
    reader.fail(matrix.offset, "array of " + std::to_string(matrix.content.size()) + " bytes, expected a multiple of 8");
  }
  const Element flags = reader.expect(kMiUint32, "array flags");
  if (flags.content.size() < 8) reader.fail(flags.offset, "array flags hold " + std::to_string(flags.content.size()) + " bytes, expected 8");
  const std::uint32_t cls = reader.u32At(flags.content, 0) & 0xFFU;
  const std::size_t count = elementCount(reader, reader.expect(kMiInt32, "array dimensions"));
  if (cls == kObjectClass) reader.expect(kMiInt8, "object class name");
  reader.expect(kMiInt8, "array name");
  const std::size_t at = reader.offset();
  const std::size_t bytes = reader.rest().size();
  if (cls == kCellClass) {
    requireFits(reader, at, count, 8, bytes, "cells");
    checkChildren(reader, count, depth);
  } else if (cls == kStructClass || cls == kObjectClass) {
    const Element name_length = reader.expect(kMiInt32, "field name length");
    const std::size_t length = name_length.content.size() >= 4 ? reader.u32At(name_length.content, 0) : 0;
    const Element names = reader.expect(kMiInt8, "field names");
    const std::size_t fields = length == 0 ? 0 : names.content.size() / length;
    if (fields * length != names.content.size()) {  // libmatio would read a different layout
      reader.fail(names.offset, "field names take " + std::to_string(names.content.size()) +
                                    " bytes, expected a multiple of the name length " + std::to_string(length));
    }
    requireFits(reader, at, count, 8 * std::max<std::size_t>(fields, 1), bytes, "struct elements");
    checkChildren(reader, count * fields, depth);
  } else if (cls == kSparseClass) {
    requireFits(reader, at, reader.u32At(flags.content, 4), 4, bytes, "stored values");
  } else {
    requireFits(reader, at, count, 1, bytes, "elements");
  }
  while (!reader.atEnd()) reader.next();  // data subelements (real, imaginary, ir, jc…) fit in the array
}

/// The element `top` is at, which the file ends in.
MatCut cutElement(ElementReader& top, bool swap) {
  MatCut cut;
  cut.at = top.offset();
  cut.swap = swap;
  const std::span<const unsigned char> rest = top.rest();
  try {
    top.next();
  } catch (const FileError& error) {
    cut.what = error.what();  // "PATH: byte N: data element declares N bytes, M left"
  }
  if (rest.size() >= 8 && top.u32At(rest, 0) == kMiCompressed) {
    cut.compressed = true;
    cut.element = inflateElement(Element{kMiCompressed, rest.subspan(8), cut.at}, top);
  } else {
    cut.element.assign(rest.begin(), rest.end());
  }
  return cut;
}

}  // namespace

std::vector<unsigned char> inflateElement(const Element& compressed, const ElementReader& reader) {
  std::vector<unsigned char> out;
  if (compressed.content.size() > std::numeric_limits<uInt>::max()) {
    reader.fail(compressed.offset, "compressed variable larger than zlib can take in one call");
  }
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) reader.fail(compressed.offset, "zlib cannot start inflating");
  stream.next_in = const_cast<unsigned char*>(compressed.content.data());  // zlib's API is not const
  stream.avail_in = static_cast<uInt>(compressed.content.size());
  int status = Z_OK;
  while (status == Z_OK) {
    if (out.size() >= kMaxInflatedMatBytes) break;
    const std::size_t done = out.size();
    out.resize(std::min(kMaxInflatedMatBytes, std::max<std::size_t>(2 * done, 4096)));
    stream.next_out = out.data() + done;
    stream.avail_out = static_cast<uInt>(out.size() - done);
    status = inflate(&stream, Z_NO_FLUSH);
    out.resize(done + (out.size() - done - stream.avail_out));
  }
  inflateEnd(&stream);
  if (status == Z_OK) reader.fail(compressed.offset, "compressed variable inflates to more than " + std::to_string(kMaxInflatedMatBytes) + " bytes");
  if (status != Z_STREAM_END && status != Z_BUF_ERROR) reader.fail(compressed.offset, "compressed variable does not inflate (zlib error " + std::to_string(status) + ")");
  return out;
}

bool hasMat5Header(std::span<const unsigned char> file) {
  return file.size() >= kMatHeaderBytes &&
         ((file[126] == 'I' && file[127] == 'M') || (file[126] == 'M' && file[127] == 'I'));
}

std::optional<MatCut> checkMatSizes(std::span<const unsigned char> file, const std::string& path,
                                    std::vector<unsigned char>* uncompressed) {
  if (uncompressed != nullptr) uncompressed->clear();
  if (!hasMat5Header(file)) return std::nullopt;  // not this format: the caller says so
  const bool swap = file[126] == 'M' && file[127] == 'I';  // written big-endian: "MI" read byte by byte
  const unsigned version = swap ? (file[124] << 8U) | file[125] : (file[125] << 8U) | file[124];
  if (version != 0x0100) return std::nullopt;  // 7.3 (HDF5) or unknown: not walked
  ElementReader top(file.subspan(kMatHeaderBytes), kMatHeaderBytes, swap, path);
  std::vector<unsigned char> copy(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(kMatHeaderBytes));
  bool compressed = false;
  while (!top.atEnd()) {
    if (top.cutShort()) {
      if (uncompressed != nullptr) uncompressed->clear();
      return cutElement(top, swap);
    }
    const std::size_t begin = top.offset();
    const Element e = top.next();
    if (e.type == kMiMatrix) checkArray(e, swap, path, 0);
    if (e.type != kMiCompressed) {
      if (uncompressed != nullptr) copy.insert(copy.end(), file.begin() + static_cast<std::ptrdiff_t>(begin), file.begin() + static_cast<std::ptrdiff_t>(top.offset()));
      continue;
    }
    const std::vector<unsigned char> inflated = inflateElement(e, top);
    const std::string where = path + " (variable compressed at byte " + std::to_string(e.offset) + ", inflated)";
    ElementReader inner(inflated, 0, swap, where);
    while (!inner.atEnd()) {
      const Element variable = inner.next();
      if (variable.type == kMiMatrix) checkArray(variable, swap, where, 0);
    }
    compressed = true;
    if (uncompressed != nullptr) copy.insert(copy.end(), inflated.begin(), inflated.end());
  }
  if (uncompressed != nullptr && compressed) *uncompressed = std::move(copy);
  return std::nullopt;
}

}  // namespace sonarmap::detail
