#pragma once
/// @file mat_fixture.hpp
/// Test helper: writes small MAT-files shaped like the CRAS log (or deliberately not) with libmatio.

#include <matio.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace sonarmap::test {

/// One element of the `parsedData` struct array to write.
struct MatBeam {
  double time = 0.0;
  double angle = 0.0;
  double step_dist = 0.0125313;
  std::vector<double> intensities = std::vector<double>(10, 0.0);
  matio_classes scalar_class = MAT_C_SINGLE;     ///< class of time, angle and step_dist
  matio_classes intensity_class = MAT_C_UINT8;   ///< class of intensities
  /// Stored as whole bytes whatever the class (MATLAB's narrower storage of a double array), when set.
  bool intensities_stored_as_bytes = false;
};

inline matvar_t* makeMatVector(matio_classes cls, const std::vector<double>& values) {
  size_t dims[2] = {1, values.size()};
  switch (cls) {
    case MAT_C_SINGLE: {
      std::vector<float> data(values.begin(), values.end());
      return Mat_VarCreate(nullptr, MAT_C_SINGLE, MAT_T_SINGLE, 2, dims, data.data(), 0);
    }
    case MAT_C_DOUBLE: {
      std::vector<double> data(values);
      return Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, data.data(), 0);
    }
    case MAT_C_UINT8: {
      std::vector<std::uint8_t> data(values.begin(), values.end());
      return Mat_VarCreate(nullptr, MAT_C_UINT8, MAT_T_UINT8, 2, dims, data.data(), 0);
    }
    case MAT_C_INT16: {
      std::vector<std::int16_t> data(values.begin(), values.end());
      return Mat_VarCreate(nullptr, MAT_C_INT16, MAT_T_INT16, 2, dims, data.data(), 0);
    }
    default:
      throw std::logic_error("makeMatVector: class not supported by the fixture");
  }
}

/// A 1×n array of class `cls` whose values are stored as miUINT8 (libmatio writes the data type it
/// is given and reads it back into the class).
inline matvar_t* makeByteStoredVector(matio_classes cls, const std::vector<double>& values) {
  size_t dims[2] = {1, values.size()};
  std::vector<std::uint8_t> data(values.begin(), values.end());
  return Mat_VarCreate(nullptr, cls, MAT_T_UINT8, 2, dims, data.data(), 0);
}

/// Writes `beams` as the struct array `variable` with the given fields (a subset of time, angle,
/// step_dist, intensities, to make a field go missing).
inline void writeCrasMat(const std::string& path, const std::vector<MatBeam>& beams,
                         const std::vector<const char*>& fields = {"time", "angle", "step_dist", "intensities"},
                         const char* variable = "parsedData", matio_compression compression = MAT_COMPRESSION_NONE) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) throw std::runtime_error("cannot create " + path);
  size_t dims[2] = {1, beams.size()};
  std::vector<const char*> names(fields);
  names.push_back(nullptr);  // the field list is NULL-terminated
  matvar_t* array = Mat_VarCreateStruct2(variable, 2, dims, names.data());
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const MatBeam& b = beams[i];
    for (const char* f : fields) {
      const std::string field(f);
      matvar_t* value = field == "intensities" && b.intensities_stored_as_bytes ? makeByteStoredVector(b.intensity_class, b.intensities)
                        : field == "intensities" ? makeMatVector(b.intensity_class, b.intensities)
                        : field == "time"      ? makeMatVector(b.scalar_class, {b.time})
                        : field == "angle"     ? makeMatVector(b.scalar_class, {b.angle})
                                               : makeMatVector(b.scalar_class, {b.step_dist});
      Mat_VarSetStructFieldByName(array, f, i, value);
    }
  }
  Mat_VarWrite(mat, array, compression);
  Mat_VarFree(array);
  Mat_Close(mat);
}

/// Writes a plain 1×n double variable.
inline void writeDoubleMat(const std::string& path, const char* variable, const std::vector<double>& values) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) throw std::runtime_error("cannot create " + path);
  size_t dims[2] = {1, values.size()};
  std::vector<double> data(values);
  matvar_t* var = Mat_VarCreate(variable, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, data.data(), 0);
  Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE);
  Mat_VarFree(var);
  Mat_Close(mat);
}

}  // namespace sonarmap::test
