#include <cmath>

#include "numpy_checks.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::python {

void throwValueError(const std::string& message) { throw sonarmap::ValueError(message); }

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    if (d > 0) text.append(", ");
    text.append(std::to_string(array.shape(d)));
  }
  if (array.ndim() == 1) text += ",";
  return text + ")";
}

namespace {

/// `object` as a numpy array without conversion of its dtype (lists become arrays of their natural dtype).
py::array asArray(const py::handle& object, const char* name) {
  if (py::isinstance<py::array>(object)) return py::reinterpret_borrow<py::array>(object);
  try {
    return py::array(py::module_::import("numpy").attr("asarray")(object));
  } catch (const py::error_already_set&) {
    throwValueError(std::string(name) + " must be a numpy array");
  }
}

void requireDtype(const py::array& array, const py::dtype& expected, const char* name, const char* what) {
  if (!array.dtype().is(expected) && !array.dtype().equal(expected)) {
    throwValueError(std::string(name) + " must have dtype " + what + ", got " +
                    py::str(array.dtype()).cast<std::string>() + " (convert explicitly, e.g. np.asarray(" + name +
                    ", dtype=np." + what + "))");
  }
}

}  // namespace

PointsView::PointsView(py::array_t<double> array)
    : array_(std::move(array)),
      base_(reinterpret_cast<const char*>(array_.data())),
      rows_(static_cast<std::size_t>(array_.ndim() == 1 ? 1 : array_.shape(0))),
      row_stride_(array_.ndim() == 1 ? 0 : array_.strides(0)),
      col_stride_(array_.ndim() == 1 ? array_.strides(0) : array_.strides(1)) {}

PointsView requirePoints(const py::handle& object, const char* name, bool allow_single) {
  py::array array = asArray(object, name);
  // Lists of Python floats arrive as float64; lists of ints as int64: accept those as numbers.
  if (!py::isinstance<py::array>(object) && array.dtype().kind() == 'i') array = array.attr("astype")("float64");
  requireDtype(array, py::dtype::of<double>(), name, "float64");
  const bool single = allow_single && array.ndim() == 1 && array.shape(0) == 3;
  if (!single && !(array.ndim() == 2 && array.shape(1) == 3)) {
    throwValueError(std::string(name) + " must have shape (N, 3) (x, y, z in metres per row), got " + shapeText(array));
  }
  PointsView view(py::reinterpret_borrow<py::array_t<double>>(array));
  for (std::size_t i = 0; i < view.size(); ++i) {
    if (!view[i].allFinite()) {
      throwValueError(std::string(name) + " row " + std::to_string(i) + " is not finite (NaN or inf); drop such rows " +
                      "first, e.g. points[np.isfinite(points).all(axis=1)]");
    }
  }
  return view;
}

Eigen::Vector3d requirePoint(const py::handle& object, const char* name) {
  py::array array = asArray(object, name);
  if (array.dtype().kind() == 'i') array = array.attr("astype")("float64");
  requireDtype(array, py::dtype::of<double>(), name, "float64");
  if (!(array.ndim() == 1 && array.shape(0) == 3)) {
    throwValueError(std::string(name) + " must have shape (3,) (x, y, z in metres), got " + shapeText(array));
  }
  PointsView view(py::reinterpret_borrow<py::array_t<double>>(array));
  const Eigen::Vector3d point = view[0];
  if (!point.allFinite()) throwValueError(std::string(name) + " must be finite, got NaN or inf");
  return point;
}

py::array_t<std::uint8_t> requireBytes1d(const py::handle& object, const char* name) {
  py::array array = asArray(object, name);
  requireDtype(array, py::dtype::of<std::uint8_t>(), name, "uint8");
  if (array.ndim() != 1) throwValueError(std::string(name) + " must be 1-D (bins,), got " + shapeText(array));
  return py::reinterpret_borrow<py::array_t<std::uint8_t>>(array);
}

py::array_t<double, py::array::c_style> requireFloat64(const py::handle& object, const char* name, int ndim) {
  py::array array = asArray(object, name);
  if (!py::isinstance<py::array>(object) && array.dtype().kind() == 'i') array = array.attr("astype")("float64");
  requireDtype(array, py::dtype::of<double>(), name, "float64");
  if (array.ndim() != ndim) {
    throwValueError(std::string(name) + " must have " + std::to_string(ndim) + " dimension(s), got shape " +
                    shapeText(array));
  }
  return py::array_t<double, py::array::c_style>::ensure(array);
}

py::array_t<double> toPointsArray(const std::vector<Eigen::Vector3d>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  double* data = out.mutable_data();
  for (std::size_t i = 0; i < points.size(); ++i) {
    data[3 * i] = points[i].x();
    data[3 * i + 1] = points[i].y();
    data[3 * i + 2] = points[i].z();
  }
  return out;
}

}  // namespace sonarmap::python

#include "navigation_arrays.hpp"
#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/formats/ros_bag_mounting.hpp"

namespace sonarmap::python {

py::array_t<double> navArray(const NavTrack& track) {
  py::array_t<double> out({static_cast<py::ssize_t>(track.size()), py::ssize_t{7}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < track.size(); ++i) {
    const NavSample& fix = track[i];
    const double row[7] = {fix.time_s, fix.position_ned_m.x(), fix.position_ned_m.y(), fix.position_ned_m.z(),
                           fix.roll_rad, fix.pitch_rad, fix.yaw_rad};
    for (int c = 0; c < 7; ++c) view(i, c) = row[c];
  }
  return out;
}

NavTrack navTrackForLog(const py::object& nav, const SonarLog& log, double nav_time_offset_s,
                        std::optional<Eigen::Isometry3d>* sonar_to_body) {
  if (py::isinstance<py::str>(nav) || py::hasattr(nav, "__fspath__")) {
    const std::string path = py::module_::import("os").attr("fspath")(nav).cast<std::string>();
    NavigationSource source = readNavigation(path);
    alignNavigationClock(source, log.clock_utc_s, nav_time_offset_s);
    if (const std::optional<LogFormat> format = logFormatOfPath(path); sonar_to_body && format && isRosLog(*format)) {
      if (const std::optional<RosBagMounting> mounting = readRosBagMounting(path, log.frame_id, source.body_frame)) {
        *sonar_to_body = mounting->sonar_to_body;
      }
    }
    return std::move(source.track);
  }
  if (!std::isfinite(nav_time_offset_s)) throwValueError("nav_time_offset_s must be finite");
  NavTrack track = navTrackOf(nav);
  for (NavSample& fix : track) fix.time_s += nav_time_offset_s;
  return track;
}

NavTrack navTrackOf(const py::object& nav) {
  if (py::isinstance<py::str>(nav) || py::hasattr(nav, "__fspath__")) {  // a path: str or os.PathLike
    return readNavigation(py::module_::import("os").attr("fspath")(nav).cast<std::string>()).track;  // CSV, ROS log, BlueROV2 log
  }
  const auto array = requireFloat64(nav, "nav", 2);
  if (array.shape(1) != 7) {
    throwValueError("nav must have shape (N, 7): time_s, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad; got " +
                    shapeText(array));
  }
  auto view = array.unchecked<2>();
  NavTrack track(static_cast<std::size_t>(array.shape(0)));
  for (std::size_t i = 0; i < track.size(); ++i) {
    for (int c = 0; c < 7; ++c) {
      if (!std::isfinite(view(i, c))) throwValueError("nav row " + std::to_string(i) + " is not finite (NaN or inf)");
    }
    track[i].time_s = view(i, 0);
    track[i].position_ned_m = Eigen::Vector3d(view(i, 1), view(i, 2), view(i, 3));
    track[i].roll_rad = view(i, 4);
    track[i].pitch_rad = view(i, 5);
    track[i].yaw_rad = view(i, 6);
  }
  return track;
}

}  // namespace sonarmap::python
