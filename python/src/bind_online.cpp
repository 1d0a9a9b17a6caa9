// sonarmap.OnlineMapper: beams mapped as they arrive (mapping/online_mapper.hpp), the one mapping
// path: map_sonar_log is a loop over the same C++ OnlineMapper, so in sweep mode the two give the
// same map byte for byte.
#include <memory>
#include <numbers>

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
                                         const std::string& format, const py::kwargs& kwargs) {
  const MappingArguments args = mappingArguments(kwargs);
  const MapperOptions options = withSonarBeam(toMapperOptions(args), args, nominalBeam(parseLogFormat(format)));
  if (!mounting.is_none() && !nav) throwValueError("mounting needs nav=True");
  if (!nav) return std::make_unique<OnlineMapper>(options, integrationOf(show));
  std::vector<double> values;
  if (!mounting.is_none()) values = mounting.cast<std::vector<double>>();
  return std::make_unique<OnlineMapper>(options, sonarToBodyOfMounting(values), integrationOf(show));
}

Beam beamOf(double time_s, double bearing_rad, double bin_length_m, const py::object& intensities,
            std::optional<double> intensity_span_db) {
  const py::array_t<std::uint8_t> bins = requireBytes1d(intensities, "intensities");
  Beam beam;
  beam.time_s = time_s;
  beam.bearing_rad = bearing_rad;
  beam.bin_length_m = bin_length_m;
  beam.intensity_span_db = intensity_span_db;
  auto view = bins.unchecked<1>();
  beam.intensities.resize(static_cast<std::size_t>(view.shape(0)));
  for (py::ssize_t i = 0; i < view.shape(0); ++i) beam.intensities[static_cast<std::size_t>(i)] = view(i);
  return beam;
}

}  // namespace

void bindOnline(py::module_& m) {
  py::class_<OnlineMapper, std::unique_ptr<OnlineMapper>>(m, "OnlineMapper", R"doc(
Maps beams as they arrive from a sonar (C++ sonarmap::OnlineMapper). Beams are fed in recording
order; the mapper forms sweeps itself (a full turn, a sector reversal, a range change) and
integrates each once it is final and, with navigation, once the fixes cover it: map() is
map_sonar_log's map of the sweeps so far, byte for byte. show="beam" also shows each beam as it
arrives on a provisional layer (shown_map()), detected with the last whole sweep's calibration,
until its sweep is integrated (the latency of a beam, not of a turn); show="sweep" shows nothing
before.
)doc")
      .def(py::init(&makeMapper), py::arg("nav") = false, py::arg("mounting") = py::none(),
           py::arg("show") = "sweep", py::arg("format") = "csv",
           R"doc(A mapper with map_sonar_log's keyword options (the CLI's names and units).

nav: False: the sonar static at the map origin; True: beams placed by the fixes given to
add_nav_fix (NED, body FRD), mounted by ``mounting`` (x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg;
default upright and aligned). show: "sweep" or "beam". format: whose nominal beam widths
apply when beam_width_deg / vertical_aperture_deg are not given ("csv": Tritech 3° × 35°).
Raises sonarmap.ValueError for invalid options; TypeError for an unknown keyword.)doc")
      .def(
          "add_beam",
          [](OnlineMapper& mapper, double time_s, double bearing_rad, double bin_length_m, const py::object& intensities,
             std::optional<double> intensity_span_db) {
            Beam beam = beamOf(time_s, bearing_rad, bin_length_m, intensities, intensity_span_db);
            py::gil_scoped_release release;
            mapper.addBeam(std::move(beam));
          },
          py::arg("time_s"), py::arg("bearing_rad"), py::arg("bin_length_m"), py::arg("intensities"),
          py::arg("intensity_span_db") = py::none(),
          R"doc(The next beam: time in seconds (the navigation's clock), bearing in radians (sonar frame), bin
length in metres (> 0), intensities uint8 (bins,), optionally the dB span of 0…255. May integrate a
sweep it completes (the GIL is released). Raises sonarmap.ValueError for a bad bin length or after finish().)doc")
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
      .def_property_readonly("sweeps_integrated", &OnlineMapper::sweepsIntegrated, "Sweeps integrated so far.")
      .def_property_readonly("beams_pending", &OnlineMapper::beamsPending, "Beams received and not yet integrated.")
      .def_property_readonly("beams_unshown", &OnlineMapper::beamsUnshown,
                             "Beams received and in neither map() nor shown_map() (the newest).");
}

}  // namespace sonarmap::python
