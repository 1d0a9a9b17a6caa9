#pragma once
// Checks and conversions of numpy arrays handed to the module: shapes, dtypes and finiteness are
// verified before any C++ work, and the failures raise sonarmap.ValueError naming the argument,
// what was expected and what was given. Arrays are read in place (strided, no copy); only the
// library's own containers (std::vector<Eigen::Vector3d>, Beam::intensities) are filled by copy.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

namespace sonarmap::python {

namespace py = pybind11;

/// A read-only (N, 3) float64 view onto a numpy array, strided, without copying.
class PointsView {
 public:
  PointsView(py::array_t<double> array);  // NOLINT: built by requirePoints only
  std::size_t size() const { return rows_; }
  Eigen::Vector3d operator[](std::size_t i) const {
    const auto* row = base_ + static_cast<std::ptrdiff_t>(i) * row_stride_;
    return {*reinterpret_cast<const double*>(row), *reinterpret_cast<const double*>(row + col_stride_),
            *reinterpret_cast<const double*>(row + 2 * col_stride_)};
  }

 private:
  py::array_t<double> array_;  // keeps the buffer alive
  const char* base_;
  std::size_t rows_;
  std::ptrdiff_t row_stride_;
  std::ptrdiff_t col_stride_;
};

/// `object` as (N, 3) float64 points, each finite.
/// @throws sonarmap.ValueError when it is not a numpy-convertible array of dtype float64 (no silent
///         conversion of float32 or integers), not of shape (N, 3) (a single (3,) point is accepted
///         as (1, 3) when `allow_single`), or holds NaN or ±inf (naming the first bad row).
PointsView requirePoints(const py::handle& object, const char* name, bool allow_single = false);

/// `object` as one finite point (3,) of float64 (a list or tuple of three numbers is accepted).
/// @throws sonarmap.ValueError otherwise.
Eigen::Vector3d requirePoint(const py::handle& object, const char* name);

/// `object` as a 1-D uint8 array (a beam's intensities). @throws sonarmap.ValueError otherwise.
py::array_t<std::uint8_t> requireBytes1d(const py::handle& object, const char* name);

/// `object` as a contiguous float64 array of `ndim` dimensions (any dtype convertible without loss
/// is NOT accepted: float64 only). @throws sonarmap.ValueError otherwise.
py::array_t<double, py::array::c_style> requireFloat64(const py::handle& object, const char* name, int ndim);

/// Raises sonarmap.ValueError with `message` (a C++ sonarmap::ValueError, translated).
[[noreturn]] void throwValueError(const std::string& message);

/// "(3, 4)" for an array's shape.
std::string shapeText(const py::array& array);

/// A numpy array of `values` (copied).
template <class T>
py::array_t<T> toArray(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

/// An (N, 3) float64 array of `points` (copied).
py::array_t<double> toPointsArray(const std::vector<Eigen::Vector3d>& points);

}  // namespace sonarmap::python
