// sonarmap.OnlineMapper: beams mapped as they arrive (mapping/online_mapper.hpp), the one mapping
// path: map_sonar_log is a loop over the same C++ OnlineMapper, so in sweep mode the two give the
// same map byte for byte when the mapper has the log's options (log=: mappingOptionsForLog) and
// each beam every field of the log's.
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "navigation_arrays.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/mapping/online_mapper.hpp"

namespace sonarmap::python {
namespace {

OnlineIntegration integrationOf(const std::string& show) {
  if (show == "sweep") return OnlineIntegration::kSweep;
  if (show == "beam") return OnlineIntegration::kProvisionalBeams;
  throwValueError("show expects 'sweep' or 'beam', got '" + show + "'");
}

std::unique_ptr<OnlineMapper> makeMapper(bool nav, const py::object& mounting, const std::string& show,
                                         const py::object& format, const PySonarLog* log, const py::kwargs& kwargs) {
  const MappingArguments args = mappingArguments(kwargs);
  if (!mounting.is_none() && !nav) throwValueError("mounting needs nav=True");
  std::optional<NominalBeam> beam = namedSonarBeam(format);
  if (!beam && log != nullptr) beam = log->beam;
  if (!beam && !(args.beam_width_given && args.vertical_aperture_given)) {
    throwValueError("OnlineMapper needs the sonar's beam: name its format (" + sonarBeamsText() +
                    "), give log=, the SonarLog it will be fed, or give beam_width_deg and vertical_aperture_deg");
  }
  MapperOptions options = beam ? withSonarBeam(toMapperOptions(args), args, *beam) : toMapperOptions(args);
  if (log != nullptr) {
    py::gil_scoped_release release;
    options = mappingOptionsForLog(options, log->log);  // map_sonar_log's: the resolution of the whole log
  }
  if (!nav) return std::make_unique<OnlineMapper>(options, integrationOf(show));
  std::vector<double> values;
  if (!mounting.is_none()) values = mounting.cast<std::vector<double>>();
  return std::make_unique<OnlineMapper>(options, sonarToBodyOfMounting(values), integrationOf(show));
}

/// A recorded value of a beam's optional field: None or NaN (a SonarLog column's mark) is none.
std::optional<double> recorded(std::optional<double> value) {
  return value && !std::isnan(*value) ? value : std::nullopt;
}

Beam beamOf(double time_s, double bearing_rad, double bin_length_m, const py::object& intensities,
            std::optional<double> intensity_span_db, std::optional<int> gain_setting,
            std::optional<double> pulse_length_m) {
  const py::array_t<std::uint8_t> bins = requireBytes1d(intensities, "intensities");
  Beam beam;
  beam.time_s = time_s;
  beam.bearing_rad = bearing_rad;
  beam.bin_length_m = bin_length_m;
  beam.intensity_span_db = recorded(intensity_span_db);
  if (gain_setting && *gain_setting >= 0) beam.gain_setting = gain_setting;  // negative: none (SonarLog's -1)
  beam.pulse_length_m = recorded(pulse_length_m);
  auto view = bins.unchecked<1>();
  beam.intensities.resize(static_cast<std::size_t>(view.shape(0)));
  for (py::ssize_t i = 0; i < view.shape(0); ++i) beam.intensities[static_cast<std::size_t>(i)] = view(i);
  return beam;
}

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

}  // namespace

void bindOnline(py::module_& m) {
  const std::string init_doc = R"doc(A mapper with map_sonar_log's keyword options (the CLI's names and units).

nav: False: the sonar static at the map origin; True: beams placed by the fixes given to
add_nav_fix (NED, body FRD), mounted by ``mounting`` (x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg;
default upright and aligned). show: "sweep" or "beam".
format: the sonar's format (read_sonar_log's names), whose nominal beam widths apply where
beam_width_deg / vertical_aperture_deg are not given: )doc" + sonarBeamsText() + R"doc( (the beam
CSV and the ROS logs name no sonar: the Micron's). Nothing else of the mapping depends on it.
log: the sonarmap.SonarLog this mapper will be fed, or None. Given, its sonar's beam applies (the
beam its file records, else its format's; format= overrides it) and the options left on "auto"
are resolved for the whole log as map_sonar_log resolves them: the resolution of the range scale
most of its beams use, the work budget (max_voxel_updates_per_beam) checked. Its beams fed in
order (add_beams, or add_beam with every field) then give map_sonar_log(log)'s map byte for byte,
and `sonarmap map`'s. Without log, an automatic resolution follows the first sweep's reach
(about 256 voxels) and coarsens as a longer range scale comes, since a stream does not know which
scale most of its beams will use (docs/python.md: a Ping360 log of 2 m power-on pings, 10 m turns
and 20 m sectors ends at 0.1 m where map_sonar_log, following the 10 m turns, gives 0.05 m); give
resolution= then.
One of format, log, or both beam_width_deg and vertical_aperture_deg is required: the beams of a
Ping360 and of a Tritech head differ.
Raises sonarmap.ValueError for invalid options, no sonar named, an unknown format, a log whose
work exceeds the budget; TypeError for an unknown keyword or a log that is not a SonarLog.)doc";
  py::class_<OnlineMapper, std::unique_ptr<OnlineMapper>>(m, "OnlineMapper", R"doc(
Maps beams as they arrive from a sonar (C++ sonarmap::OnlineMapper). Beams are fed in recording
order; the mapper forms sweeps itself (a full turn, a sector reversal, a change of range or gain)
and integrates each once it is final and, with navigation, once the fixes cover it: map() is
map_sonar_log's map of the sweeps so far, byte for byte, when the mapper has the same options
(log=, or the same resolution) and each beam every field the log's reader filled. show="beam"
also shows each beam as it arrives on a provisional layer (shown_map()), detected with the last
whole sweep's calibration, until its sweep is integrated (the latency of a beam, not of a turn);
show="sweep" shows nothing before.
)doc")
      .def(py::init(&makeMapper), py::arg("nav") = false, py::arg("mounting") = py::none(),
           py::arg("show") = "sweep", py::arg("format") = py::none(), py::arg("log") = nullptr, init_doc.c_str())
      .def(
          "add_beam",
          [](OnlineMapper& mapper, double time_s, double bearing_rad, double bin_length_m, const py::object& intensities,
             std::optional<double> intensity_span_db, std::optional<int> gain_setting,
             std::optional<double> pulse_length_m) {
            Beam beam = beamOf(time_s, bearing_rad, bin_length_m, intensities, intensity_span_db, gain_setting,
                               pulse_length_m);
            py::gil_scoped_release release;
            mapper.addBeam(std::move(beam));
          },
          py::arg("time_s"), py::arg("bearing_rad"), py::arg("bin_length_m"), py::arg("intensities"),
          py::arg("intensity_span_db") = py::none(), py::arg("gain_setting") = py::none(),
          py::arg("pulse_length_m") = py::none(),
          R"doc(The next beam, with the fields of the C++ Beam (sonar/beam.hpp) and SonarLog's columns of the
same names: time_s, seconds (the navigation's clock); bearing_rad, radians in the sonar frame
(clockwise from ahead); bin_length_m, metres (> 0); intensities, uint8 (bins,), bin 0 nearest.
What the head recorded of its settings, each None when not recorded:
intensity_span_db: the dB span of 0…255 (> 0); NaN: not stated (SonarLog's NaN: a Ping360's
counts, whose scale depends on its gain, have none): 45 dB is assumed, as in `sonarmap map` (the
keyword intensity_span, when given, replaces every beam's span).
gain_setting: the receiver gain setting in the head's own units (Ping360: 0 low, 1 normal, 2 high;
SeaNet: the gain byte); negative: none (SonarLog's -1). A change of gain, like a change of range,
ends a sweep: each setting is calibrated on its own beams.
pulse_length_m: the transmitted pulse's length in range, c·τ/2, metres (> 0); NaN: none. The
detector never asks an echo to be longer than the pulse.
A beam given without a field its log's reader filled is not the log's beam: the map may differ
from map_sonar_log's. May integrate a sweep it completes (the GIL is released). Raises
sonarmap.ValueError for a bin length, span or pulse length that is not finite and > 0, or after
finish().)doc")
      .def(
          "add_beams",
          [](OnlineMapper& mapper, const PySonarLog& log, std::size_t first, std::optional<std::size_t> last) {
            const std::size_t end = std::min(last.value_or(log.log.beams.size()), log.log.beams.size());
            py::gil_scoped_release release;
            for (std::size_t i = first; i < end; ++i) mapper.addBeam(log.log.beams[i]);
          },
          py::arg("log"), py::arg("first") = 0, py::arg("last") = py::none(),
          "Feeds beams [first, last) of a sonarmap.SonarLog in order (copied), GIL released.")
      .def(
          "add_nav_fix",
          [](OnlineMapper& mapper, double time_s, double x_m, double y_m, double z_m, double roll_rad, double pitch_rad,
             double yaw_rad) {
            NavSample fix;
            fix.time_s = time_s;
            fix.position_ned_m = Eigen::Vector3d(x_m, y_m, z_m);
            fix.roll_rad = roll_rad;
            fix.pitch_rad = pitch_rad;
            fix.yaw_rad = yaw_rad;
            py::gil_scoped_release release;
            mapper.addNavFix(fix);
          },
          py::arg("time_s"), py::arg("x_m"), py::arg("y_m"), py::arg("z_m"), py::arg("roll_rad") = 0.0,
          py::arg("pitch_rad") = 0.0, py::arg("yaw_rad") = 0.0,
          R"doc(The next navigation fix: seconds, NED metres (x north, y east, z down), body FRD Z-Y-X radians.
Raises sonarmap.ValueError for a non-finite fix, one not after the previous, or without nav=True.)doc")
      .def(
          "add_nav",
          [](OnlineMapper& mapper, const py::object& nav) {
            const NavTrack track = navTrackOf(nav);
            py::gil_scoped_release release;
            for (const NavSample& fix : track) mapper.addNavFix(fix);
          },
          py::arg("nav"), "Feeds every fix of an (N, 7) navigation array (or CSV path) in order; see add_nav_fix.")
      .def(
          "finish",
          [](OnlineMapper& mapper) {
            py::gil_scoped_release release;
            mapper.finish();
          },
          "The end of the stream: every held sweep is integrated; further beams are refused. Idempotent.")
      .def(
          "map",
          [](const OnlineMapper& mapper) {
            py::gil_scoped_release release;
            return OccupancyMap{mapInFrame(mapper.mapSnapshot(), kDefaultMapFrame), mapper.statsSnapshot(),
                                std::nullopt, std::nullopt, std::nullopt, kDefaultMapFrame};
          },
          "A copy of the map as of the last integrated sweep, with its stats (sonarmap.OccupancyMap), in ENU (x east, "
          "y north, z up) as map_sonar_log's default.")
      .def(
          "shown_map",
          [](const OnlineMapper& mapper) {
            py::gil_scoped_release release;
            return OccupancyMap{mapInFrame(mapper.shownSnapshot(), kDefaultMapFrame), mapper.statsSnapshot(),
                                std::nullopt, std::nullopt, std::nullopt, kDefaultMapFrame};
          },
          "map() with the provisional beams' log-odds added (show=\"beam\"; else map()).")
      .def(
          "stats", [](const OnlineMapper& mapper) { return mapper.statsSnapshot(); },
          "A copy of the counts as of the last integrated sweep (sonarmap.MappingStats).")
      .def_property_readonly(
          "resolution", [](const OnlineMapper& mapper) { return mapper.optionsSnapshot().resolution_m; },
          "The voxel edge, metres; None while it is automatic and no sweep is integrated yet (see __init__).")
      .def_property_readonly(
          "beam_width_deg", [](const OnlineMapper& mapper) { return degrees(mapper.optionsSnapshot().beam_width_rad); },
          "The horizontal beam width mapped with, degrees (the sonar's, or beam_width_deg).")
      .def_property_readonly(
          "vertical_aperture_deg",
          [](const OnlineMapper& mapper) { return degrees(mapper.optionsSnapshot().vertical_aperture_rad); },
          "The vertical beam width mapped with, degrees (the sonar's, or vertical_aperture_deg).")
      .def_property_readonly("sweeps_integrated", &OnlineMapper::sweepsIntegrated, "Sweeps integrated so far.")
      .def_property_readonly("beams_pending", &OnlineMapper::beamsPending, "Beams received and not yet integrated.")
      .def_property_readonly("beams_unshown", &OnlineMapper::beamsUnshown,
                             "Beams received and in neither map() nor shown_map() (the newest).");
}

}  // namespace sonarmap::python
