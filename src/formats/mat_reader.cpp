/// @file mat_reader.cpp
/// readCrasMat: CRAS Micron MAT-file → SonarLog, via libmatio (see mat_reader.hpp).

#include "sonarmap/formats/mat_reader.hpp"

#include <matio.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mat_cut.hpp"
#include "mat_size_check.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr const char* kVariable = "parsedData";
constexpr const char* kFields[] = {"time", "angle", "step_dist", "intensities"};
/// Bytes a struct field takes in a level-5 file at the least: the tag of its miMATRIX element.
constexpr std::uintmax_t kMinFieldBytes = 8;
/// zlib cannot expand data more than about 1032:1, so a compressed variable holds at most this
/// many times the file's size once inflated; declared sizes above that are not believed.
constexpr std::uintmax_t kMaxInflation = 1032;
/// A numeric array may store its values in a narrower type than its class (MAT-File Format,
/// "Numeric Arrays": a double array of whole counts stored as miUINT8, as the CRAS log's
/// intensities are); libmatio allocates the class: at most 8 bytes a byte stored (double or
/// 64-bit from 8-bit, complex from twice as many stored bytes).
constexpr std::uintmax_t kMaxWidening = 8;

// ---- libmatio plumbing: RAII handles and a quiet logger ----------------------------------------

struct MatCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct MatVarFreer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using MatFile = std::unique_ptr<mat_t, MatCloser>;
using MatVar = std::unique_ptr<matvar_t, MatVarFreer>;

thread_local std::string g_last_matio_message;

/// Keeps libmatio's last message instead of letting it print to stderr (the library never prints).
void quietMatioLog(int /*log_level*/, char* message) {
  g_last_matio_message = message != nullptr ? message : "";
}

void installQuietMatioLog() {
  static std::once_flag once;
  std::call_once(once, [] { Mat_LogInitFunc("sonarmap", &quietMatioLog); });
}

[[noreturn]] void throwFileError(const std::string& path, const std::string& what) {
  std::string message = "'" + path + "' (a CRAS .mat log): " + what;
  if (!g_last_matio_message.empty()) message += " (libmatio: " + g_last_matio_message + ")";
  throw FileError(message);
}

// ---- one beam ------------------------------------------------------------------------------------

/// Either a beam or why element `index` of parsedData is not one.
struct BeamOrReason {
  std::optional<Beam> beam;
  std::string reason;
};

/// The product of the declared dimensions; SIZE_MAX when it overflows (dimensions come from the file).
std::size_t elementCount(const matvar_t& var) {
  if (var.rank <= 0 || var.dims == nullptr) return 0;
  std::size_t count = 1;
  for (int d = 0; d < var.rank; ++d) {
    if (var.dims[d] != 0 && count > SIZE_MAX / var.dims[d]) return SIZE_MAX;
    count *= var.dims[d];
  }
  return count;
}

/// "parsedData(5) [index 4]": element `index` as MATLAB (1-based) and C++ count it.
std::string elementName(std::size_t index) {
  return std::string(kVariable) + "(" + std::to_string(index + 1) + ") [index " + std::to_string(index) + "]";
}

/// "1×5604", for messages.
std::string dimsText(const matvar_t& var) {
  std::string text;
  for (int d = 0; d < var.rank && var.dims != nullptr; ++d) text += (d > 0 ? "×" : "") + std::to_string(var.dims[d]);
  return text.empty() ? "no dimensions" : text;
}

/// MATLAB's name of a class, for messages.
std::string className(matio_classes cls) {
  switch (cls) {
    case MAT_C_DOUBLE: return "double";
    case MAT_C_SINGLE: return "single";
    case MAT_C_INT8: return "int8";
    case MAT_C_UINT8: return "uint8";
    case MAT_C_INT16: return "int16";
    case MAT_C_UINT16: return "uint16";
    case MAT_C_INT32: return "int32";
    case MAT_C_UINT32: return "uint32";
    case MAT_C_INT64: return "int64";
    case MAT_C_UINT64: return "uint64";
    case MAT_C_CHAR: return "char";
    case MAT_C_STRUCT: return "struct";
    case MAT_C_CELL: return "cell";
    default: return "class #" + std::to_string(static_cast<int>(cls));
  }
}

/// Checks that `var` holds a real single or double scalar and returns it, or the problem.
std::optional<double> readScalar(const matvar_t* var, std::string_view field, std::string& reason) {
  if (var == nullptr || var->data == nullptr) {
    reason = "field '" + std::string(field) + "' is missing or unreadable";
    return std::nullopt;
  }
  if (var->isComplex != 0 || elementCount(*var) != 1) {
    reason = "field '" + std::string(field) + "' is not a real 1×1 value";
    return std::nullopt;
  }
  double value = 0.0;
  if (var->class_type == MAT_C_SINGLE && var->nbytes >= sizeof(float)) {
    value = static_cast<double>(*static_cast<const float*>(var->data));
  } else if (var->class_type == MAT_C_DOUBLE && var->nbytes >= sizeof(double)) {
    value = *static_cast<const double*>(var->data);
  } else {
    reason = "field '" + std::string(field) + "' is " + className(var->class_type) + ", expected single (or double)";
    return std::nullopt;
  }
  if (!std::isfinite(value)) {
    reason = "field '" + std::string(field) + "' is not finite";
    return std::nullopt;
  }
  return value;
}

/// Converts stored intensities to 0…255 bytes; `false` when a value is not an integer in range.
template <typename T>
bool toBytes(const T* values, std::size_t count, std::vector<std::uint8_t>& out) {
  out.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double v = static_cast<double>(values[i]);
    if (!(v >= 0.0 && v <= 255.0)) return false;
    const auto byte = static_cast<std::uint8_t>(v);  // in range: truncation is floor
    if (static_cast<double>(byte) != v) return false;
    out[i] = byte;
  }
  return true;
}

/// Reads the `intensities` field: a real vector, uint8 or (as in the published CRAS file, despite
/// its description) double or single holding integers 0…255.
std::optional<std::vector<std::uint8_t>> readIntensities(const matvar_t* var, std::string& reason) {
  if (var == nullptr || var->data == nullptr || elementCount(*var) == 0) {
    reason = "field 'intensities' is missing, empty or unreadable";
    return std::nullopt;
  }
  const std::size_t count = elementCount(*var);
  if (var->isComplex != 0 || var->rank != 2 || (var->dims[0] != 1 && var->dims[1] != 1)) {
    reason = "field 'intensities' is not a real 1×N vector";
    return std::nullopt;
  }
  std::vector<std::uint8_t> bytes;
  bool ok = false;
  if (var->class_type == MAT_C_UINT8 && var->nbytes >= count) {
    ok = toBytes(static_cast<const std::uint8_t*>(var->data), count, bytes);
  } else if (var->class_type == MAT_C_DOUBLE && var->nbytes >= count * sizeof(double)) {
    ok = toBytes(static_cast<const double*>(var->data), count, bytes);
  } else if (var->class_type == MAT_C_SINGLE && var->nbytes >= count * sizeof(float)) {
    ok = toBytes(static_cast<const float*>(var->data), count, bytes);
  } else {
    reason = "field 'intensities' is " + className(var->class_type) + ", expected uint8 (or double/single integers)";
    return std::nullopt;
  }
  if (!ok) {
    reason = "field 'intensities' holds a value that is not an integer in [0, 255]";
    return std::nullopt;
  }
  return bytes;
}

/// Bearing in [0, 2π), clockwise from ahead, from the CRAS head angle in degrees (the Micron's
/// SeaNet bearing, clockwise, ahead at 180°): radians(angle − 180) = radians(angle + 180) mod 2π.
double bearingFromCrasAngle(double angle_deg) {
  double deg = std::fmod(angle_deg + 180.0, 360.0);
  if (deg < 0.0) deg += 360.0;
  double rad = deg * std::numbers::pi / 180.0;
  return rad >= 2.0 * std::numbers::pi ? 0.0 : rad;
}

BeamOrReason readBeam(matvar_t* data, std::size_t index) {
  BeamOrReason out;
  const auto field = [&](const char* name) { return Mat_VarGetStructFieldByName(data, name, index); };
  const auto time_s = readScalar(field("time"), "time", out.reason);
  if (!time_s) return out;
  const auto angle_deg = readScalar(field("angle"), "angle", out.reason);
  if (!angle_deg) return out;
  const auto bin_length_m = readScalar(field("step_dist"), "step_dist", out.reason);
  if (!bin_length_m) return out;
  if (*bin_length_m <= 0.0) {
    out.reason = "field 'step_dist' is " + std::to_string(*bin_length_m) + ", expected > 0 m";
    return out;
  }
  auto intensities = readIntensities(field("intensities"), out.reason);
  if (!intensities) return out;
  out.beam = Beam{*time_s, bearingFromCrasAngle(*angle_deg), *bin_length_m, std::move(*intensities), {}, {}, {}};
  return out;
}

// ---- the log -------------------------------------------------------------------------------------

/// The whole file, for detail::checkMatSizes.
std::vector<unsigned char> fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);  // at the end: its position is the size
  const std::streamoff size = in.tellg();
  if (!in || size < 0) throwFileError(path, "cannot be read");
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(bytes.data()), size);
  if (in.gcount() != size) throwFileError(path, "cannot be read");
  return bytes;
}

/// Checks the file before libmatio sees it: it takes any file without a level-5 header for a
/// version 4 file (which cannot hold structs), and it allocates from declared sizes unchecked.
/// @return the element the file ends in when it is cut short (then libmatio must not read it).
/// @param uncompressed  the file with its compressed variables inflated, when it has any
///                      (detail::checkMatSizes); empty otherwise.
std::optional<detail::MatCut> checkMat(const std::string& path, std::vector<unsigned char>& uncompressed) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throwFileError(path, "no such file (or not a regular file)");
  const std::vector<unsigned char> bytes = fileBytes(path);
  if (!detail::hasMat5Header(bytes)) {
    throwFileError(path, "has no 128-byte MATLAB 5 header, expected a MATLAB 5 (or 7.3) MAT-file");
  }
  return detail::checkMatSizes(bytes, path, &uncompressed);
}

/// The uncompressed copy of a file as a file libmatio can open by name (it opens by path only): an
/// anonymous in-memory file (memfd_create(2)) reached as /proc/self/fd/N, closed with this object.
/// `name()` is empty when the system offers none; the caller then reads the original.
class MemoryMatFile {
 public:
  explicit MemoryMatFile(const std::vector<unsigned char>& bytes) : fd_(::memfd_create("sonarmap-mat", MFD_CLOEXEC)) {
    if (fd_ < 0) return;
    std::size_t written = 0;
    while (written < bytes.size()) {
      const ssize_t n = ::write(fd_, bytes.data() + written, bytes.size() - written);
      if (n <= 0) return;
      written += static_cast<std::size_t>(n);
    }
    const std::string name = "/proc/self/fd/" + std::to_string(fd_);
    if (::access(name.c_str(), R_OK) == 0) name_ = name;
  }
  ~MemoryMatFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  MemoryMatFile(const MemoryMatFile&) = delete;
  MemoryMatFile& operator=(const MemoryMatFile&) = delete;
  const std::string& name() const { return name_; }

 private:
  int fd_;
  std::string name_;
};

/// Opens `file` with libmatio; messages name `path`, the log the user gave.
MatFile openMat(const std::string& file, const std::string& path) {
  MatFile mat(Mat_Open(file.c_str(), MAT_ACC_RDONLY));
  if (!mat) throwFileError(path, "cannot be opened as a MATLAB MAT-file");
  return mat;
}

/// True when the struct array `var` holds a field pointer for each of its elements × fields, so
/// that Mat_VarGetStructField* stays within its data (libmatio indexes by the declared dimensions).
bool structIsComplete(const matvar_t& var) {
  const std::size_t fields = Mat_VarGetNumberOfFields(const_cast<matvar_t*>(&var));
  const std::size_t elements = elementCount(var);
  return var.data != nullptr && fields > 0 && elements <= SIZE_MAX / fields / sizeof(matvar_t*) &&
         var.nbytes == elements * fields * sizeof(matvar_t*);
}

/// Rejects declared sizes that the file cannot hold, from the variable's header alone (before any
/// data is read): the struct's elements × fields × 8 bytes must fit in the `budget` bytes the file
/// can store, and the sum over its fields of elements × their class's size in kMaxWidening times it.
void checkDeclaredSizes(matvar_t& info, std::uintmax_t budget, const std::string& path) {
  const std::size_t fields = Mat_VarGetNumberOfFields(&info);
  const std::size_t elements = elementCount(info);
  if (fields != 0 && elements > budget / kMinFieldBytes / fields) {
    throwFileError(path, std::string("'") + kVariable + "' declares " + dimsText(info) + " elements of " +
                             std::to_string(fields) + " fields (at least " + std::to_string(kMinFieldBytes) +
                             " bytes each) but the file can hold at most " + std::to_string(budget) + " bytes");
  }
  if (!structIsComplete(info)) throwFileError(path, std::string("the fields of '") + kVariable + "' cannot be read");
  std::uintmax_t left = budget * kMaxWidening;  // declared bytes of the classes still believable
  for (std::size_t i = 0; i < elements; ++i) {
    for (std::size_t f = 0; f < fields; ++f) {
      const matvar_t* field = Mat_VarGetStructFieldByIndex(&info, f, i);
      if (field == nullptr) continue;  // reported per beam
      const std::size_t size = std::max<std::size_t>(Mat_SizeOfClass(field->class_type), 1);
      const std::size_t count = elementCount(*field);
      if (count > left / size) {
        throwFileError(path, elementName(i) + ": field '" + (field->name != nullptr ? field->name : "?") +
                                 "' declares " + dimsText(*field) + " elements of " + std::to_string(size) +
                                 " bytes, more than the " + std::to_string(budget * kMaxWidening) +
                                 " bytes the file's " + std::to_string(budget) + " can hold for all fields");
      }
      left -= count * size;
    }
  }
}

/// The most bytes the variables of a file of `file_bytes` can store: the file's size, or
/// kMaxInflation times it for a compressed (zlib, or HDF5 7.3) variable.
std::uintmax_t byteBudget(const mat_t& mat, const matvar_t& info, std::uintmax_t file_bytes) {
  const bool compressed =
      info.compression != MAT_COMPRESSION_NONE || Mat_GetVersion(const_cast<mat_t*>(&mat)) == MAT_FT_MAT73;
  return compressed ? file_bytes * kMaxInflation : file_bytes;
}

/// Reads the header of `parsedData` and checks its class and declared sizes. For an uncompressed
/// variable libmatio reads no field data yet; for a zlib-compressed one it has inflated the fields'
/// data with their headers (it cannot skip through a compressed stream).
MatVar checkedParsedDataInfo(mat_t* mat, const std::string& path, std::uintmax_t file_bytes) {
  MatVar info(Mat_VarReadInfo(mat, kVariable));
  if (!info) throwFileError(path, std::string("no readable variable '") + kVariable + "'");
  if (info->class_type != MAT_C_STRUCT) {
    throwFileError(path, std::string("variable '") + kVariable + "' is " + className(info->class_type) +
                             ", expected a struct array");
  }
  if (elementCount(*info) == 0) throwFileError(path, std::string("'") + kVariable + "' is empty");
  checkDeclaredSizes(*info, byteBudget(*mat, *info, file_bytes), path);
  return info;
}

void requireFields(matvar_t& data, const std::string& path);

/// @param file_bytes  the size of the file libmatio reads (the original or its uncompressed copy).
MatVar readParsedData(mat_t* mat, const std::string& path, std::uintmax_t file_bytes) {
  // The checked header, its field data read in place: Mat_VarRead would read the header again
  // (a second pass through the inflated variable, half the reading time of the CRAS log).
  // checkedParsedDataInfo has checked that it is a complete struct array; reading its fields'
  // data does not change that.
  MatVar data = checkedParsedDataInfo(mat, path, file_bytes);
  if (Mat_VarReadDataAll(mat, data.get()) != MATIO_E_NO_ERROR) {
    throwFileError(path, std::string("variable '") + kVariable + "' cannot be read");
  }
  requireFields(*data, path);
  return data;
}

/// @throws FileError unless `data` has every field of kFields.
void requireFields(matvar_t& data, const std::string& path) {
  const unsigned field_count = Mat_VarGetNumberOfFields(&data);
  char* const* names = Mat_VarGetStructFieldnames(&data);
  for (const char* wanted : kFields) {
    bool found = false;
    for (unsigned f = 0; f < field_count && names != nullptr; ++f) {
      found = found || (names[f] != nullptr && std::string_view(names[f]) == wanted);
    }
    if (!found) throwFileError(path, std::string("'") + kVariable + "' has no field '" + wanted + "'");
  }
}

/// The most common bin count among the beams (ties: the larger count).
std::size_t dominantBinCount(const std::vector<BeamOrReason>& read) {
  std::map<std::size_t, std::size_t> histogram;
  for (const auto& r : read) {
    if (r.beam) ++histogram[r.beam->intensities.size()];
  }
  std::size_t best = 0, best_votes = 0;
  for (const auto& [bins, votes] : histogram) {
    if (votes >= best_votes) best = bins, best_votes = votes;
  }
  return best;
}

/// The valid beams of `read` in file order, and why the others were skipped (a beam whose bin
/// count is not the dominant one is skipped too). @throws FileError when a valid beam's time is
/// before the previous valid beam's.
SonarLog collectBeams(std::vector<BeamOrReason>& read, const std::string& path) {
  const std::size_t bins = dominantBinCount(read);
  SonarLog log;
  log.beams.reserve(read.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    auto& r = read[i];
    if (r.beam && r.beam->intensities.size() != bins) {
      r.reason = "has " + std::to_string(r.beam->intensities.size()) + " bins, the log's beams have " +
                 std::to_string(bins);
      r.beam.reset();
    }
    if (r.beam && !log.beams.empty() && r.beam->time_s < log.beams.back().time_s) {
      throwFileError(path, elementName(i) + ": field 'time' is " + std::to_string(r.beam->time_s) +
                               " s, before the previous beam's " + std::to_string(log.beams.back().time_s) +
                               " s; times must not go backwards");
    }
    if (r.beam) {
      log.beams.push_back(std::move(*r.beam));
    } else {
      ++log.skipped_beams;
      log.skip_reasons.push_back(path + ": " + elementName(i) + ": " + r.reason);
    }
  }
  return log;
}

/// The beams of the struct array `data` (its fields checked), in file order.
/// @throws FileError when none is valid.
SonarLog beamsOf(matvar_t& data, const std::string& path) {
  const std::size_t count = elementCount(data);
  std::vector<BeamOrReason> read;
  read.reserve(count);
  for (std::size_t i = 0; i < count; ++i) read.push_back(readBeam(&data, i));
  SonarLog log = collectBeams(read, path);
  if (log.beams.empty()) {
    throwFileError(path, std::string("no valid beam; ") + kVariable + "(1): " + read.front().reason);
  }
  return log;
}

/// The beams of the whole elements of `parsedData` before the cut `cut` (a file cut short), and a
/// skip reason for the cut.
/// @throws FileError when the file ends in another variable, or before parsedData's first element.
SonarLog readCutMat(const detail::MatCut& cut, const std::string& path) {
  const detail::CutStruct recovered = detail::wholeStructElements(cut, kVariable);
  MatVar data(recovered.whole);
  if (!recovered.is_variable) {  // libmatio would read into the cut: not given the file
    throw FileError(cut.what + " (cut short, in a variable that is not a whole '" + kVariable + "' struct array)");
  }
  if (!data) throw FileError(cut.what + " (cut short before the first whole element of '" + kVariable + "')");
  requireFields(*data, path);
  SonarLog log = beamsOf(*data, path);
  ++log.skipped_beams;
  log.skip_reasons.push_back(cut.what + " (cut short): the first " + std::to_string(elementCount(*data)) + " of the " +
                             std::to_string(recovered.declared) + " elements of '" + kVariable +
                             "' read, the rest skipped");
  return log;
}

}  // namespace

SonarLog readCrasMat(const std::string& path) {
  installQuietMatioLog();
  g_last_matio_message.clear();
  std::vector<unsigned char> uncompressed;
  if (const std::optional<detail::MatCut> cut = checkMat(path, uncompressed)) return readCutMat(*cut, path);
  std::optional<MemoryMatFile> copy;
  if (!uncompressed.empty()) copy.emplace(uncompressed);
  std::uintmax_t file_bytes = uncompressed.size();
  std::vector<unsigned char>().swap(uncompressed);  // the copy holds it now
  const bool from_copy = copy && !copy->name().empty();
  if (!from_copy) {
    std::error_code ec;
    file_bytes = std::filesystem::file_size(path, ec);
    if (ec) throwFileError(path, "its size cannot be read");
  }
  MatFile mat = openMat(from_copy ? copy->name() : path, path);
  MatVar data = readParsedData(mat.get(), path, file_bytes);
  return beamsOf(*data, path);
}

}  // namespace sonarmap
