/// @file mat_reader.cpp
/// readCrasMat: CRAS Micron MAT-file → SonarLog, via libmatio (see mat_reader.hpp).

#include "sonarmap/sonar/mat_reader.hpp"

#include <matio.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr const char* kVariable = "parsedData";
constexpr const char* kFields[] = {"time", "angle", "step_dist", "intensities"};

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
  std::string message = "readCrasMat: '" + path + "': " + what;
  if (!g_last_matio_message.empty()) message += " (libmatio: " + g_last_matio_message + ")";
  throw FileError(message);
}

// ---- one beam ------------------------------------------------------------------------------------

/// Either a beam or why element `index` of parsedData is not one.
struct BeamOrReason {
  std::optional<Beam> beam;
  std::string reason;
};

std::size_t elementCount(const matvar_t& var) {
  std::size_t count = 1;
  for (int d = 0; d < var.rank; ++d) count *= var.dims[d];
  return var.rank > 0 ? count : 0;
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
    if (!(v >= 0.0 && v <= 255.0) || v != std::floor(v)) return false;
    out[i] = static_cast<std::uint8_t>(v);
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

/// Bearing in [0, 2π) from the CRAS head angle in degrees: radians(angle + 180), the authors'
/// plane convention.
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
  out.beam = Beam{*time_s, bearingFromCrasAngle(*angle_deg), *bin_length_m, std::move(*intensities)};
  return out;
}

// ---- the log -------------------------------------------------------------------------------------

MatFile openMat(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throwFileError(path, "no such file (or not a regular file)");
  MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat) throwFileError(path, "cannot be opened as a MATLAB MAT-file");
  return mat;
}

MatVar readParsedData(mat_t* mat, const std::string& path) {
  MatVar data(Mat_VarRead(mat, kVariable));
  if (!data) throwFileError(path, std::string("no readable variable '") + kVariable + "'");
  if (data->class_type != MAT_C_STRUCT) {
    throwFileError(path, std::string("variable '") + kVariable + "' is " + className(data->class_type) +
                             ", expected a struct array");
  }
  if (elementCount(*data) == 0) throwFileError(path, std::string("'") + kVariable + "' is empty");
  const unsigned field_count = Mat_VarGetNumberOfFields(data.get());
  char* const* names = Mat_VarGetStructFieldnames(data.get());
  for (const char* wanted : kFields) {
    bool found = false;
    for (unsigned f = 0; f < field_count && names != nullptr; ++f) {
      found = found || (names[f] != nullptr && std::string_view(names[f]) == wanted);
    }
    if (!found) throwFileError(path, std::string("'") + kVariable + "' has no field '" + wanted + "'");
  }
  return data;
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

}  // namespace

SonarLog readCrasMat(const std::string& path) {
  installQuietMatioLog();
  g_last_matio_message.clear();
  MatFile mat = openMat(path);
  MatVar data = readParsedData(mat.get(), path);

  const std::size_t count = elementCount(*data);
  std::vector<BeamOrReason> read;
  read.reserve(count);
  for (std::size_t i = 0; i < count; ++i) read.push_back(readBeam(data.get(), i));

  const std::size_t bins = dominantBinCount(read);
  SonarLog log;
  log.beams.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    auto& r = read[i];
    if (r.beam && r.beam->intensities.size() != bins) {
      r.reason = "has " + std::to_string(r.beam->intensities.size()) + " bins, the log's beams have " +
                 std::to_string(bins);
      r.beam.reset();
    }
    if (r.beam) {
      log.beams.push_back(std::move(*r.beam));
    } else {
      ++log.skipped_beams;
      log.skip_reasons.push_back(path + ": " + kVariable + "(" + std::to_string(i + 1) + ") [index " +
                                 std::to_string(i) + "]: " + r.reason);
    }
  }
  if (log.beams.empty()) {
    throwFileError(path, std::string("no valid beam; ") + kVariable + "(1): " + read.front().reason);
  }
  return log;
}

}  // namespace sonarmap
