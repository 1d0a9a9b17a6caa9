/// @file mat_cut.cpp
/// The whole elements of a struct array a MAT-file cut short ends in (see mat_cut.hpp).

#include "mat_cut.hpp"

#include <matio.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mat_elements.hpp"

namespace sonarmap::detail {
namespace {

constexpr std::uint32_t kComplexFlag = 0x0800;  // in the array flags (MAT-File Format, table 1-2)

using OwnedVar = std::unique_ptr<matvar_t, void (*)(matvar_t*)>;

/// Bytes of one value of the stored data type `type`; 0 for a type that is not a number.
std::size_t typeBytes(std::uint32_t type) {
  switch (type) {
    case MAT_T_INT8: case MAT_T_UINT8: return 1;
    case MAT_T_INT16: case MAT_T_UINT16: return 2;
    case MAT_T_INT32: case MAT_T_UINT32: case MAT_T_SINGLE: return 4;
    case MAT_T_INT64: case MAT_T_UINT64: case MAT_T_DOUBLE: return 8;
    default: return 0;
  }
}

/// The data type a numeric class holds its values in (as libmatio keeps them), or nothing.
std::optional<matio_types> classType(std::uint32_t cls) {
  switch (cls) {
    case MAT_C_DOUBLE: return MAT_T_DOUBLE;
    case MAT_C_SINGLE: return MAT_T_SINGLE;
    case MAT_C_INT8: return MAT_T_INT8;
    case MAT_C_UINT8: return MAT_T_UINT8;
    case MAT_C_INT16: return MAT_T_INT16;
    case MAT_C_UINT16: return MAT_T_UINT16;
    case MAT_C_INT32: return MAT_T_INT32;
    case MAT_C_UINT32: return MAT_T_UINT32;
    case MAT_C_INT64: return MAT_T_INT64;
    case MAT_C_UINT64: return MAT_T_UINT64;
    default: return std::nullopt;
  }
}

template <class T>
double as(const unsigned char* raw) {
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return static_cast<double>(value);
}

/// Stored value `i` of `data`, of data type `type`, as a double.
double valueAt(std::span<const unsigned char> data, std::size_t i, std::uint32_t type, bool swap) {
  const std::size_t n = typeBytes(type);
  unsigned char raw[8] = {};
  for (std::size_t k = 0; k < n; ++k) raw[k] = data[i * n + (swap ? n - 1 - k : k)];
  switch (type) {
    case MAT_T_INT8: return as<std::int8_t>(raw);
    case MAT_T_UINT8: return as<std::uint8_t>(raw);
    case MAT_T_INT16: return as<std::int16_t>(raw);
    case MAT_T_UINT16: return as<std::uint16_t>(raw);
    case MAT_T_INT32: return as<std::int32_t>(raw);
    case MAT_T_UINT32: return as<std::uint32_t>(raw);
    case MAT_T_SINGLE: return as<float>(raw);
    case MAT_T_INT64: return as<std::int64_t>(raw);
    case MAT_T_UINT64: return as<std::uint64_t>(raw);
    default: return as<double>(raw);
  }
}

template <class T>
void put(std::vector<unsigned char>& out, std::size_t i, double value) {
  const T stored = static_cast<T>(value);
  std::memcpy(out.data() + i * sizeof(T), &stored, sizeof(T));
}

/// `value` written as value `i` of `out`, in the class's data type `type`.
void putValue(std::vector<unsigned char>& out, std::size_t i, matio_types type, double value) {
  switch (type) {
    case MAT_T_INT8: return put<std::int8_t>(out, i, value);
    case MAT_T_UINT8: return put<std::uint8_t>(out, i, value);
    case MAT_T_INT16: return put<std::int16_t>(out, i, value);
    case MAT_T_UINT16: return put<std::uint16_t>(out, i, value);
    case MAT_T_INT32: return put<std::int32_t>(out, i, value);
    case MAT_T_UINT32: return put<std::uint32_t>(out, i, value);
    case MAT_T_SINGLE: return put<float>(out, i, value);
    case MAT_T_INT64: return put<std::int64_t>(out, i, value);
    case MAT_T_UINT64: return put<std::uint64_t>(out, i, value);
    default: return put<double>(out, i, value);
  }
}

/// A whole real numeric array (miMATRIX `matrix`) made again with libmatio, its values converted
/// from their stored type to its class's as libmatio converts them; null for any other array.
/// @throws FileError when a subelement does not fit in the array.
matvar_t* numericArray(const Element& matrix, bool swap, const std::string& where) {
  ElementReader in(matrix.content, matrix.offset + 8, swap, where);
  const Element flags = in.expect(kMiUint32, "array flags");
  if (flags.content.size() < 8) return nullptr;
  const std::uint32_t word = in.u32At(flags.content, 0);
  const std::optional<matio_types> type = classType(word & 0xFFU);
  if (!type || (word & kComplexFlag) != 0) return nullptr;
  const Element dims = in.expect(kMiInt32, "array dimensions");
  if (dims.content.size() % 4 != 0 || dims.content.size() < 8) return nullptr;
  std::vector<std::size_t> sizes;
  std::size_t count = 1;
  for (std::size_t at = 0; at < dims.content.size(); at += 4) {
    const auto dim = static_cast<std::int32_t>(in.u32At(dims.content, at));
    if (dim < 0) return nullptr;
    sizes.push_back(static_cast<std::size_t>(dim));
    count = sizes.back() == 0 ? 0 : count > matrix.content.size() ? count : count * sizes.back();
  }
  in.expect(kMiInt8, "array name");
  std::vector<unsigned char> values;
  if (count > 0) {
    const Element real = in.next();
    const std::size_t bytes = typeBytes(real.type);
    if (bytes == 0 || count > real.content.size() / bytes) return nullptr;  // its data must fill it
    values.resize(count * typeBytes(*type));
    for (std::size_t i = 0; i < count; ++i) putValue(values, i, *type, valueAt(real.content, i, real.type, swap));
  }
  return Mat_VarCreate(nullptr, static_cast<matio_classes>(word & 0xFFU), *type, static_cast<int>(sizes.size()),
                       sizes.data(), values.empty() ? nullptr : values.data(), 0);
}

}  // namespace

CutStruct wholeStructElements(const MatCut& cut, const char* name) {
  CutStruct out;
  const std::string where = "the element the file ends in";
  const std::span<const unsigned char> bytes(cut.element);
  const ElementReader tag(bytes, 0, cut.swap, where);
  if (bytes.size() < 8 || tag.u32At(bytes, 0) != kMiMatrix) return out;
  const std::size_t declared_bytes = tag.u32At(bytes, 4);
  ElementReader in(bytes.subspan(8, std::min(declared_bytes, bytes.size() - 8)), 8, cut.swap, where);
  std::vector<std::string> fields;
  try {
    const Element flags = in.expect(kMiUint32, "array flags");
    if (flags.content.size() < 8 || (in.u32At(flags.content, 0) & 0xFFU) != kStructClass) return out;
    const Element dims = in.expect(kMiInt32, "array dimensions");
    out.declared = 1;
    for (std::size_t at = 0; at + 4 <= dims.content.size(); at += 4) {
      out.declared *= static_cast<std::size_t>(std::max<std::int32_t>(0, static_cast<std::int32_t>(in.u32At(dims.content, at))));
    }
    const Element variable = in.expect(kMiInt8, "array name");
    if (std::string(variable.content.begin(), variable.content.end()) != name) return out;
    const Element length = in.expect(kMiInt32, "field name length");
    const std::size_t name_bytes = length.content.size() >= 4 ? in.u32At(length.content, 0) : 0;
    const Element names = in.expect(kMiInt8, "field names");
    if (name_bytes == 0 || names.content.size() % name_bytes != 0) return out;
    for (std::size_t at = 0; at < names.content.size(); at += name_bytes) {
      const auto first = names.content.begin() + static_cast<std::ptrdiff_t>(at);
      const auto end = std::find(first, first + static_cast<std::ptrdiff_t>(name_bytes), 0);
      fields.emplace_back(first, end);
    }
  } catch (const FileError&) {
    return out;  // the struct's header is not whole
  }
  out.is_variable = true;
  std::vector<std::vector<OwnedVar>> elements;
  for (std::size_t i = 0; i < out.declared && !fields.empty(); ++i) {
    std::vector<OwnedVar> element;
    try {
      for (std::size_t f = 0; f < fields.size(); ++f) {
        const Element field = in.next();
        matvar_t* array = field.type == kMiMatrix ? numericArray(field, cut.swap, where) : nullptr;
        if (array == nullptr) break;
        element.emplace_back(array, &Mat_VarFree);
      }
    } catch (const FileError&) {
      // the element the cut runs through
    }
    if (element.size() != fields.size()) break;
    elements.push_back(std::move(element));
  }
  if (elements.empty()) return out;
  std::vector<const char*> names;
  for (const std::string& field : fields) names.push_back(field.c_str());
  names.push_back(nullptr);
  const std::size_t dims[2] = {1, elements.size()};
  out.whole = Mat_VarCreateStruct2(name, 2, dims, names.data());
  for (std::size_t i = 0; i < elements.size() && out.whole != nullptr; ++i) {
    for (std::size_t f = 0; f < fields.size(); ++f) Mat_VarSetStructFieldByIndex(out.whole, f, i, elements[i][f].release());
  }
  return out;
}

}  // namespace sonarmap::detail
