// The sonar side: logs (formats/log_reader.hpp) as numpy arrays, sweeps (sonar/sweeps.hpp), polar
// and Cartesian images (sonar/polar.hpp) and first-obstacle detection (detection/detectors.hpp,
// through SonarMapper::detectSweep: the mapper's own cleaning and detection).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <opencv2/core.hpp>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_clock.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap::python {

void PySonarLog::cache() {
  if (cached) return;
  const std::size_t beams = log.beams.size();
  bins = 0;
  for (const Beam& beam : log.beams) bins = std::max(bins, static_cast<int>(beam.intensities.size()));
  intensities.assign(beams * static_cast<std::size_t>(bins), 0);
  valid_bins.resize(beams);
  time_s.resize(beams);
  bearing_rad.resize(beams);
  bin_length_m.resize(beams);
  intensity_span_db.resize(beams);
  gain_setting.resize(beams);
  pulse_length_m.resize(beams);
  constexpr double kNotRecorded = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t b = 0; b < beams; ++b) {
    const Beam& beam = log.beams[b];
    std::copy(beam.intensities.begin(), beam.intensities.end(), intensities.begin() + b * static_cast<std::size_t>(bins));
    valid_bins[b] = static_cast<std::int32_t>(beam.intensities.size());
    time_s[b] = beam.time_s;
    bearing_rad[b] = beam.bearing_rad;
    bin_length_m[b] = beam.bin_length_m;
    intensity_span_db[b] = beam.intensity_span_db.value_or(kNotRecorded);
    gain_setting[b] = beam.gain_setting ? static_cast<std::int32_t>(*beam.gain_setting) : -1;
    pulse_length_m[b] = beam.pulse_length_m.value_or(kNotRecorded);
  }
  cached = true;
}

namespace {

/// A read-only numpy view of `data` (shape `shape`) owned by the Python object `owner`.
template <class T>
py::array readOnlyView(const std::vector<T>& data, std::vector<py::ssize_t> shape, const py::object& owner) {
  py::array_t<T> view(shape, data.data(), owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

/// The getter of a read-only (beams,) view of the log's cached column `values`.
template <class T>
auto column(std::vector<T> PySonarLog::*values) {
  return [values](py::object self) {
    auto& log = self.cast<PySonarLog&>();
    log.cache();
    const std::vector<T>& column = log.*values;
    return readOnlyView(column, {static_cast<py::ssize_t>(column.size())}, self);
  };
}

/// A PolarImage's intensities as a writable (rows, cols) uint8 view of its cv::Mat, owned by `owner`.
py::array matView(cv::Mat& mat, const py::object& owner) {
  if (!mat.isContinuous()) mat = mat.clone();
  return py::array_t<std::uint8_t>({static_cast<py::ssize_t>(mat.rows), static_cast<py::ssize_t>(mat.cols)},
                                    {static_cast<py::ssize_t>(mat.step[0]), py::ssize_t{1}}, mat.ptr<std::uint8_t>(),
                                    owner);
}

/// A cv::Mat (CV_8U) handed to numpy without copying: the array owns the Mat through a capsule.
py::array matToArray(cv::Mat mat) {
  auto* owned = new cv::Mat(mat.isContinuous() ? mat : mat.clone());
  py::capsule owner(owned, [](void* p) { delete static_cast<cv::Mat*>(p); });
  return py::array_t<std::uint8_t>({static_cast<py::ssize_t>(owned->rows), static_cast<py::ssize_t>(owned->cols)},
                                   {static_cast<py::ssize_t>(owned->step[0]), py::ssize_t{1}},
                                   owned->ptr<std::uint8_t>(), owner);
}

/// The sweeps as an (S, 2) int64 array of [first, last_exclusive) beam indices.
py::array_t<std::int64_t> sweepArray(const std::vector<SweepRange>& sweeps) {
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(sweeps.size()), py::ssize_t{2}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    view(i, 0) = static_cast<std::int64_t>(sweeps[i].first);
    view(i, 1) = static_cast<std::int64_t>(sweeps[i].last_exclusive);
  }
  return out;
}

PySonarLog readLog(const std::filesystem::path& file, const std::string& format, const std::string& sonar_topic,
                   const std::string& bearing_unit, const std::string& bearing_direction, const std::string& timezone,
                   const std::string& msg_path) {
  const std::string path = file.string();
  PySonarLog out;
  const LogFormat log_format = inputFormat(path, format);
  const double utc_offset_s = parseUtcOffset(timezone);
  {
    py::gil_scoped_release release;
    out.log = readSonarLog(path, log_format, LogReadOptions{sonar_topic, bearing_unit, bearing_direction, utc_offset_s, msg_path});
  }
  out.format = std::string(logFormatName(log_format));
  out.beam = nominalBeam(log_format, out.log);
  return out;
}

/// A SonarLog from arrays (copied into the library's beams).
PySonarLog logFromArrays(const py::object& intensities, const py::object& time_s, const py::object& bearing_rad,
                         const py::object& bin_length_m, const py::object& valid_bins, const std::string& format) {
  py::array image = py::array::ensure(intensities);
  if (!image || !image.dtype().equal(py::dtype::of<std::uint8_t>()) || image.ndim() != 2) {
    throwValueError("intensities must be a (beams, bins) uint8 array");
  }
  const auto rows = static_cast<std::size_t>(image.shape(0));
  auto column = [&](const py::object& values, const char* name) {
    py::array_t<double, py::array::c_style> array = requireFloat64(values, name, 1);
    if (static_cast<std::size_t>(array.shape(0)) != rows) {
      throwValueError(std::string(name) + " must have one value per beam (" + std::to_string(rows) + "), got " +
                      shapeText(array));
    }
    return array;
  };
  const auto times = column(time_s, "time_s");
  const auto bearings = column(bearing_rad, "bearing_rad");
  py::array_t<double, py::array::c_style> lengths;
  if (py::isinstance<py::float_>(bin_length_m) || py::isinstance<py::int_>(bin_length_m)) {
    lengths = py::array_t<double, py::array::c_style>(static_cast<py::ssize_t>(rows));
    std::fill(lengths.mutable_data(), lengths.mutable_data() + rows, bin_length_m.cast<double>());
  } else {
    lengths = column(bin_length_m, "bin_length_m");
  }
  std::vector<std::int64_t> valid(rows, image.shape(1));
  if (!valid_bins.is_none()) {
    py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> given(valid_bins);
    if (given.ndim() != 1 || static_cast<std::size_t>(given.shape(0)) != rows) {
      throwValueError("valid_bins must have shape (beams,)");
    }
    for (std::size_t r = 0; r < rows; ++r) {
      if (given.at(r) < 0 || given.at(r) > image.shape(1)) throwValueError("valid_bins must lie in [0, bins]");
      valid[r] = given.at(r);
    }
  }
  auto view = py::reinterpret_borrow<py::array_t<std::uint8_t>>(image).unchecked<2>();
  PySonarLog out;
  out.log.beams.resize(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    Beam& beam = out.log.beams[r];
    beam.time_s = times.at(r);
    beam.bearing_rad = bearings.at(r);
    beam.bin_length_m = lengths.at(r);
    if (!std::isfinite(beam.time_s) || !std::isfinite(beam.bearing_rad) || !(beam.bin_length_m > 0.0) ||
        !std::isfinite(beam.bin_length_m)) {
      throwValueError("beam " + std::to_string(r) + ": time_s and bearing_rad must be finite and bin_length_m > 0");
    }
    beam.intensities.resize(static_cast<std::size_t>(valid[r]));
    for (std::int64_t c = 0; c < valid[r]; ++c) beam.intensities[c] = view(r, c);
  }
  const LogFormat log_format = parseLogFormat(format);
  out.format = std::string(logFormatName(log_format));
  out.beam = nominalBeam(log_format);
  return out;
}

/// The beams [first, last) of `log` as a polar image: whole sweep `sweep` (an index into
/// wholeSweeps, negative from the end), or beams [first, last), or by default the largest sweep
/// (the last on ties), the one `sonarmap map --polar-png` draws.
PolarImage polarOf(const PySonarLog& log, const std::optional<std::int64_t>& sweep,
                   const std::optional<std::int64_t>& first, const std::optional<std::int64_t>& last) {
  const std::size_t beams = log.log.beams.size();
  if (beams == 0) throwValueError("the log holds no beams");
  std::size_t from = 0, to = beams;
  if (sweep) {
    if (first || last) throwValueError("give either sweep or first/last, not both");
    const std::vector<SweepRange> sweeps = wholeSweeps(log.log.beams);
    std::int64_t index = *sweep < 0 ? *sweep + static_cast<std::int64_t>(sweeps.size()) : *sweep;
    if (index < 0 || index >= static_cast<std::int64_t>(sweeps.size())) {
      throwValueError("sweep " + std::to_string(*sweep) + " out of range: the log has " + std::to_string(sweeps.size()) +
                      " whole sweeps (log.whole_sweeps(); log.sweeps() and first/last give the partial ones)");
    }
    from = sweeps[index].first;
    to = sweeps[index].last_exclusive;
  } else if (first || last) {
    from = first ? static_cast<std::size_t>(std::max<std::int64_t>(*first, 0)) : 0;
    to = last ? static_cast<std::size_t>(std::max<std::int64_t>(*last, 0)) : beams;
  } else {
    const std::vector<SweepRange> sweeps = splitSweeps(log.log.beams);
    const SweepRange* best = &sweeps.front();
    for (const SweepRange& range : sweeps) {
      if (range.size() >= best->size()) best = &range;
    }
    from = best->first;
    to = best->last_exclusive;
  }
  py::gil_scoped_release release;
  return makePolarImage(log.log.beams, from, to);
}

PolarImage polarFromArrays(const py::object& intensities, const py::object& bearing_rad, double bin_length_m,
                           const py::object& time_s, const std::optional<double>& intensity_span_db) {
  py::array image = py::array::ensure(intensities);
  if (!image || !image.dtype().equal(py::dtype::of<std::uint8_t>()) || image.ndim() != 2) {
    throwValueError("intensities must be a (beams, bins) uint8 array");
  }
  const auto rows = static_cast<int>(image.shape(0));
  const auto cols = static_cast<int>(image.shape(1));
  const auto bearings = requireFloat64(bearing_rad, "bearing_rad", 1);
  if (bearings.shape(0) != rows) throwValueError("bearing_rad must have one value per row");
  if (!(bin_length_m > 0.0) || !std::isfinite(bin_length_m)) throwValueError("bin_length_m must be finite and > 0");
  PolarImage polar;
  polar.intensities = cv::Mat(rows, cols, CV_8U);
  auto view = py::reinterpret_borrow<py::array_t<std::uint8_t>>(image).unchecked<2>();
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) polar.intensities.at<std::uint8_t>(r, c) = view(r, c);
  }
  polar.valid_bins.assign(rows, cols);
  polar.bearing_rad.assign(bearings.data(), bearings.data() + rows);
  polar.time_s.assign(rows, 0.0);
  if (!time_s.is_none()) {
    const auto times = requireFloat64(time_s, "time_s", 1);
    if (times.shape(0) != rows) throwValueError("time_s must have one value per row");
    polar.time_s.assign(times.data(), times.data() + rows);
  }
  polar.bin_length_m = bin_length_m;
  polar.intensity_span_db = intensity_span_db;
  return polar;
}

py::dict detectionsDict(const SweepDetection& sweep) {
  const std::vector<BeamDetection>& d = sweep.detections;
  std::vector<std::int32_t> bins(d.size());
  std::vector<std::uint8_t> intensity(d.size());
  std::vector<bool> weak(d.size());
  std::vector<double> range(d.size()), water(d.size()), rise(d.size()), onset(d.size()), echo_end(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    bins[i] = d[i].obstacle_bin;
    intensity[i] = d[i].intensity;
    range[i] = d[i].hasObstacle() ? d[i].range_m : std::numeric_limits<double>::quiet_NaN();
    water[i] = d[i].water_range_m;
    rise[i] = d[i].rise_m;
    onset[i] = d[i].echo_onset_m;
    echo_end[i] = d[i].echo_end_m;
    weak[i] = d[i].weak;
  }
  py::dict out;
  out["obstacle_bin"] = toArray(bins);
  out["range_m"] = toArray(range);
  out["intensity"] = toArray(intensity);
  out["water_range_m"] = toArray(water);
  out["rise_m"] = toArray(rise);
  out["echo_onset_m"] = toArray(onset);
  out["echo_end_m"] = toArray(echo_end);
  py::array_t<bool> weak_array(static_cast<py::ssize_t>(weak.size()));
  for (std::size_t i = 0; i < weak.size(); ++i) weak_array.mutable_at(static_cast<py::ssize_t>(i)) = weak[i];
  out["weak"] = weak_array;
  out["min_range_m"] = sweep.min_range_m;
  out["threshold_db"] = sweep.calibration.threshold_db;
  return out;
}

}  // namespace

void bindSonar(py::module_& m) {
  py::class_<PySonarLog>(m, "SonarLog", R"doc(
Beams of an MSIS log in recording order (C++ sonarmap::SonarLog; paper §2.1).

Sonar frame: x along bearing 0 (ahead), y starboard, z down; bearings clockwise from +x seen from above,
radians in [0, 2π). Bin i of a beam covers ranges [i, i+1) × bin_length_m from the transducer.
The arrays are read-only numpy views onto one contiguous copy of the beams, made once on the first
access (the library keeps each beam's bins in its own vector, so a copy is unavoidable once);
later accesses copy nothing. Build a modified log with SonarLog.from_arrays.
)doc")
      .def_static("from_arrays", &logFromArrays, py::arg("intensities"), py::arg("time_s"), py::arg("bearing_rad"),
                  py::arg("bin_length_m"), py::arg("valid_bins") = py::none(), py::arg("format") = "csv",
                  R"doc(A log from arrays (copied): intensities (beams, bins) uint8; time_s (beams,) float64 seconds;
bearing_rad (beams,) float64, sonar frame; bin_length_m (beams,) float64 metres or one number;
valid_bins (beams,) integers, bins each beam really has (default: all); format names the sonar
whose nominal beam widths map_sonar_log uses by default ("csv": Tritech 3° × 35°, "ping360": 2° × 25°).
Raises sonarmap.ValueError for a wrong shape or dtype, a non-finite time or bearing, a bin length <= 0.)doc")
      .def_property_readonly(
          "intensities",
          [](py::object self) {
            auto& log = self.cast<PySonarLog&>();
            log.cache();
            return readOnlyView(log.intensities,
                                {static_cast<py::ssize_t>(log.log.beams.size()), static_cast<py::ssize_t>(log.bins)},
                                self);
          },
          "Echo intensities, uint8 (beams, bins), 0…255, bin 0 nearest; bins a beam lacks are 0 (see valid_bins).")
      .def_property_readonly(
          "valid_bins", column(&PySonarLog::valid_bins),
          "int32 (beams,): the number of real bins of each beam.")
      .def_property_readonly(
          "time_s", column(&PySonarLog::time_s),
          "float64 (beams,): time of each beam, seconds on the log's own clock (raw captures: 0).")
      .def_property_readonly(
          "bearing_rad", column(&PySonarLog::bearing_rad),
          "float64 (beams,): bearing of each beam, radians in [0, 2π), sonar frame, clockwise from +x (ahead).")
      .def_property_readonly(
          "bin_length_m", column(&PySonarLog::bin_length_m),
          "float64 (beams,): length of one bin along each beam, metres.")
      .def_property_readonly(
          "intensity_span_db", column(&PySonarLog::intensity_span_db),
          "float64 (beams,): dB span the intensities 0…255 cover, as the head states it (SeaNet: ADspan × 80 / 255). "
          "NaN: the format does not state its intensity scale in dB (a Ping360 sends counts whose scale depends on its "
          "gain; a CRAS .mat, a beam CSV without the column); the mapper then takes intensity_span= if given, else "
          "assumes 45 dB, as `sonarmap map` does (--intensity-span): its echo threshold, in dB above each sweep's "
          "measured background, becomes counts at that span.")
      .def_property_readonly(
          "gain_setting", column(&PySonarLog::gain_setting),
          "int32 (beams,): the receiver gain setting the head reported, in its own units (Ping360: 0 low, 1 normal, "
          "2 high; SeaNet: the gain byte); -1 where the format records none. A change of gain starts a sweep.")
      .def_property_readonly(
          "pulse_length_m", column(&PySonarLog::pulse_length_m),
          "float64 (beams,): the transmitted pulse's length in range, c·τ/2, metres (Ping360: its transmit duration); "
          "NaN where the format records none. The detector never asks an echo to be longer.")
      .def_property_readonly(
          "clock_utc_s", [](const PySonarLog& log) { return log.log.clock_utc_s; },
          "UTC (seconds since 1970) at time_s = 0 when the file says (a ROS log: 0; a Ping Viewer log named "
          "yyyyMMdd-hhmmsszzz: its start), else None.")
      .def_property_readonly("skipped_beams", [](const PySonarLog& log) { return log.log.skipped_beams; },
                             "Malformed beams the reader dropped.")
      .def_property_readonly("skip_reasons", [](const PySonarLog& log) { return log.log.skip_reasons; },
                             "One line per skipped beam.")
      .def_property_readonly("format", [](const PySonarLog& log) { return log.format; },
                             "The format read (\"mat\", \"csv\", \"v4log\", \"seanet\", \"ping360\", \"rosbag\", \"mcap\", \"rosbag2\") or \"simulated\".")
      .def_property_readonly(
          "nominal_beam_deg",
          [](const PySonarLog& log) {
            return py::make_tuple(log.beam.width_rad * 180.0 / std::numbers::pi,
                                  log.beam.vertical_aperture_rad * 180.0 / std::numbers::pi);
          },
          "(horizontal width, vertical aperture) in degrees of the sonar that recorded the log: map_sonar_log's defaults.")
      .def(
          "sweeps", [](const PySonarLog& log) { return sweepArray(splitSweeps(log.log.beams)); },
          "Every sweep (a full turn, a sector pass, the beams between range or gain changes, the log's partial first "
          "and last sweeps) as int64 (S, 2) [first, last_exclusive) beam indices, covering all beams in order.")
      .def(
          "whole_sweeps", [](const PySonarLog& log) { return sweepArray(wholeSweeps(log.log.beams)); },
          "The whole sweeps among sweeps(): full turns, and sector passes from one turning point to the other (not "
          "the log's partial first or last sweep, nor one cut by a range or gain change), as int64 (W, 2) "
          "[first, last_exclusive) beam indices. polar_image(log, sweep=k) draws whole sweep k.")
      .def(
          "write_csv",
          [](const PySonarLog& log, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            writeBeamCsv(path.string(), log.log);
          },
          py::arg("path"), "Writes the beams as a beam CSV (docs/formats.md), atomically. Raises sonarmap.FileError.")
      .def("__len__", [](const PySonarLog& log) { return log.log.beams.size(); })
      .def("__repr__", [](const PySonarLog& log) {
        return "SonarLog(" + std::to_string(log.log.beams.size()) + " beams, format=" + log.format +
               ", skipped_beams=" + std::to_string(log.log.skipped_beams) + ")";
      });

  m.def("read_sonar_log", &readLog, py::arg("path"), py::arg("format") = "auto", py::arg("sonar_topic") = "",
        py::arg("bearing_unit") = "auto", py::arg("bearing_direction") = "cw", py::arg("timezone") = "UTC", py::arg("msg_path") = "",
        R"doc(Reads a sonar log: CRAS Micron ``.mat``, beam ``.csv``, SeaNet ``.V4LOG``, raw SeaNet capture
``.seanet``, Ping360 ``.bin``, ROS 1 bag ``.bag``, ROS 2 MCAP ``.mcap``, rosbag2 SQLite ``.db3`` or bag
folder (by extension, any case), or any name with ``format`` = "mat", "csv", "v4log", "seanet", "ping360",
"rosbag", "mcap", "rosbag2" (the CLI's --format).
For a ROS log: ``sonar_topic`` (default: found by its fields), ``bearing_unit`` "auto" | "deg" | "rad" |
"grad" and ``bearing_direction`` "cw" | "ccw" (the CLI's --sonar-topic, --bearing-unit,
--bearing-direction; docs/formats.md). ``timezone``: the recording computer's offset from UTC for a log
named in local time ("UTC", "+03:30"; the CLI's --timezone): a Ping Viewer log named yyyyMMdd-hhmmsszzz
then has ``clock_utc_s``. ``msg_path``: a folder of ``.msg`` files (PKG/msg/NAME.msg) for the types a
rosbag2 SQLite log before ROS 2 Iron names without definitions (the CLI's --msg-path). Malformed beams are dropped and counted (skipped_beams). Returns
sonarmap.SonarLog. Raises sonarmap.FileError for an unknown extension or a file the reader rejects;
sonarmap.ValueError for an unknown format name, bearing unit or direction.)doc");

  py::class_<PolarImage>(m, "PolarImage", R"doc(
The polar image of consecutive beams (C++ sonarmap::PolarImage; paper §2.1, Fig. 3): row r is
beam r, column c is bin c. ``intensities`` is a writable uint8 (rows, cols) view of the C++ image
(no copy): changes are seen by detect_obstacles and cartesian_image.
)doc")
      .def(py::init(&polarFromArrays), py::arg("intensities"), py::arg("bearing_rad"), py::arg("bin_length_m"),
           py::arg("time_s") = py::none(), py::arg("intensity_span_db") = py::none(),
           R"doc(A polar image from arrays (copied): intensities (rows, bins) uint8; bearing_rad (rows,) float64
radians, sonar frame; bin_length_m metres > 0; time_s (rows,) float64 seconds (default 0);
intensity_span_db: dB span of 0…255 (default: 45 dB where needed). Raises sonarmap.ValueError.)doc")
      .def_property_readonly(
          "intensities", [](py::object self) { return matView(self.cast<PolarImage&>().intensities, self); },
          "uint8 (rows, bins) view of the image; bins at or beyond valid_bins[row] are 0.")
      .def_property_readonly("valid_bins", [](const PolarImage& p) { return toArray(p.valid_bins); },
                             "int32 (rows,): real bins of each row (a copy).")
      .def_property_readonly("bearing_rad", [](const PolarImage& p) { return toArray(p.bearing_rad); },
                             "float64 (rows,): bearing of each row, radians, sonar frame (a copy).")
      .def_property_readonly("time_s", [](const PolarImage& p) { return toArray(p.time_s); },
                             "float64 (rows,): time of each row, seconds (a copy).")
      .def_property_readonly("bin_length_m", [](const PolarImage& p) { return p.bin_length_m; }, "Bin length, metres.")
      .def_property_readonly(
          "range_m",
          [](const PolarImage& p) {
            std::vector<double> ranges(static_cast<std::size_t>(p.cols()));
            for (std::size_t c = 0; c < ranges.size(); ++c) ranges[c] = (static_cast<double>(c) + 0.5) * p.bin_length_m;
            return toArray(ranges);
          },
          "float64 (bins,): range of each bin's centre, metres.")
      .def_property_readonly("intensity_span_db", [](const PolarImage& p) { return p.intensity_span_db; },
                             "dB span of 0…255 recorded by the log, or None.")
      .def("__repr__", [](const PolarImage& p) {
        return "PolarImage(" + std::to_string(p.rows()) + " beams x " + std::to_string(p.cols()) +
               " bins, bin_length_m=" + std::to_string(p.bin_length_m) + ")";
      });

  m.def("polar_image", &polarOf, py::arg("log"), py::arg("sweep") = py::none(), py::arg("first") = py::none(),
        py::arg("last") = py::none(),
        R"doc(The polar image of beams of ``log``: whole sweep ``sweep`` (an index into log.whole_sweeps(),
negative from the end: ``sweep=-1`` is the last whole sweep, never the few beams a log ends
on), or beams [first, last) (any part of the log, e.g. a row of log.sweeps()), or by default the
largest sweep (the last on ties), the one ``sonarmap map --polar-png`` draws. Returns sonarmap.PolarImage (rows = beams, cols = the largest
bin count). Raises sonarmap.ValueError for an empty or out-of-range selection, a beam without
bins, or beams of different bin lengths.)doc");

  m.def(
      "cartesian_image",
      [](const PolarImage& polar, std::optional<double> pixel_size_m, double beam_width_deg) {
        const double pixel_m = pixel_size_m.value_or(polar.bin_length_m);
        cv::Mat image;
        {
          py::gil_scoped_release release;
          image = makeCartesianImage(polar, pixel_m, beam_width_deg * std::numbers::pi / 180.0);
        }
        return matToArray(image);
      },
      py::arg("polar"), py::arg("pixel_size_m") = py::none(), py::arg("beam_width_deg") = 3.0,
      R"doc(Top view of a polar image (paper §2.1, Fig. 4): uint8 (S, S), S = 2·ceil(R / pixel_size_m) + 1,
R = bins × bin_length_m. Seen from above: the sonar is the centre pixel, +x (bearing 0, ahead) UP,
+y (bearing 90°, starboard; bearings turn clockwise) to the right: row 0 is the top, so show it with
``plt.imshow(img, extent=[-h, h, -h, h])``, h = (S / 2) · pixel_size_m. Angles between beams at
most ``beam_width_deg`` apart are interpolated; pixels no beam covers are 0.
pixel_size_m: metres per pixel (default: the bin length). The array owns the image (no copy).
Raises sonarmap.ValueError for an empty image, a pixel size <= 0, a beam width out of (0, 360],
or an image side above 20,000 pixels.)doc");

  const std::string detect_doc = R"doc(First obstacle along each beam of one sweep's polar image, as the mapper finds it
(SonarMapper::detectSweep: calibration, self-reflection removal, smoothing, detection; paper
§8.2, §9; detectors.hpp). Keyword options are map_sonar_log's detection options with the CLI's
names and units (sonarmap.mapping_options() with stage "detection"): )doc" + mappingKeywordsDoc(true) + R"doc(.
The input is not modified. Returns a dict of arrays over the rows: obstacle_bin int32 (-1: none),
range_m float64 (leading edge, metres; NaN: none), intensity uint8, water_range_m, rise_m,
echo_onset_m, echo_end_m float64 (metres; echo_end_m: where the obstacle's loud echo falls back
below half the threshold, NaN without an obstacle), weak bool (a weak return: no loud echo, certain
by its bins' evidence against the water, the evidence detector); and min_range_m, threshold_db (floats), cleaned (the PolarImage the
detector saw). Raises sonarmap.ValueError for an invalid option; TypeError for an unknown keyword.)doc";
  m.def(
      "detect_obstacles",
      [](const PolarImage& polar, const py::kwargs& kwargs) {
        const MapperOptions options = toMapperOptions(mappingArguments(kwargs));
        PolarImage cleaned = polar;
        cleaned.intensities = polar.intensities.clone();
        SweepDetection sweep;
        {
          py::gil_scoped_release release;
          const SonarMapper mapper(options);
          sweep = mapper.detectSweep(cleaned);
        }
        py::dict out = detectionsDict(sweep);
        out["cleaned"] = py::cast(std::move(cleaned));
        return out;
      },
      py::arg("polar"), detect_doc.c_str());
}

}  // namespace sonarmap::python
