/// @file dataflash_navigation.cpp
/// readDataflashNavigation: an ArduPilot dataflash log → NavTrack (see vehicle_log_navigation.hpp;
/// the records: dataflash_log.hpp).

#include <algorithm>
#include <filesystem>
#include <map>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "dataflash_log.hpp"
#include "reader_support.hpp"
#include "vehicle_track.hpp"

namespace sonarmap {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
/// 1980-01-06 00:00 UTC, GPS time's zero, in seconds since 1970; GPS − UTC = 18 s since 2017-01-01
/// (IERS Bulletin C 52), the leap seconds ArduPilot's AP_GPS does not remove from GWk, GMS.
constexpr double kGpsEpochUtc_s = 315964800.0;
constexpr double kGpsLeap_s = 18.0;
constexpr double kSecondsPerWeek = 604800.0;
constexpr double kGpsFix3d = 3.0;

class DataflashNavigation {
 public:
  explicit DataflashNavigation(const VehicleLogOptions& options) : options_(options) {}

  void visit(const detail::DataflashRecord& r) {
    const std::string& name = r.format().name;
    const std::optional<double> time_us = r.value("TimeUS");
    if (!time_us) return;
    const double t = *time_us / 1e6;
    if (name == "ATT") {
      const auto roll = r.value("Roll"), pitch = r.value("Pitch"), yaw = r.value("Yaw");
      if (roll && pitch && yaw) attitude_.push_back({t, *roll * kRadPerDeg, *pitch * kRadPerDeg, *yaw * kRadPerDeg});
    } else if (name == "XKF1" || name == "NKF1") {
      if (const auto core = r.value("C"); core && *core != 0.0) return;
      const auto n = r.value("PN"), e = r.value("PE"), d = r.value("PD");
      if (n && e && d) ekf_[name].push_back({t, Eigen::Vector3d(*n, *e, *d)});
    } else if (name == "BARO" || name == "BAR2" || name == "BAR3") {
      const auto pressure = r.value("Press");
      const int instance = name == "BARO" ? static_cast<int>(r.value("I").value_or(0.0)) : name[3] - '1';
      if (pressure) pressure_pa_[instance].push_back({t, Eigen::Vector3d(0.0, 0.0, *pressure)});
    } else if (name == "GPS") {
      const auto status = r.value("Status"), week = r.value("GWk"), ms = r.value("GMS");
      if (!clock_utc_s_ && status && week && ms && *status >= kGpsFix3d && *week > 0.0) {
        clock_utc_s_ = kGpsEpochUtc_s + *week * kSecondsPerWeek + *ms / 1000.0 - kGpsLeap_s - t;
      }
      // The instance 0 receiver's 3D fixes: Lat, Lng (1e-7 degrees), Alt (metres above mean sea level).
      if (const auto instance = r.value("I"); instance && *instance != 0.0) return;
      const auto lat = r.value("Lat"), lon = r.value("Lng"), alt = r.value("Alt");
      if (!status || *status < kGpsFix3d || !lat || !lon) return;
      const GeodeticFix fix{t, {*lat, *lon, alt.value_or(0.0)}};
      try {
        requireGeodetic(fix.point, "GPS record at boot time " + std::to_string(t) + " s");
      } catch (const ValueError& error) {
        ++gps_rejected_;
        if (gps_reason_.empty()) gps_reason_ = error.what();
        return;
      }
      if (!gps_.empty() && !(t > gps_.back().time_s)) return;
      gps_.push_back(fix);
    }
  }

  NavigationSource finish(const std::string& source, const detail::DataflashScan& scan) {
    if (attitude_.empty()) {
      throw FileError("'" + source + "': no ATT record in " + std::to_string(scan.records) + " records" +
                      (scan.stop_note.empty() ? std::string() : " (" + scan.stop_note + ")"));
    }
    const char* ekf = ekf_.count("XKF1") ? "XKF1" : (ekf_.count("NKF1") ? "NKF1" : nullptr);
    std::vector<detail::PositionSample> depths;
    std::string depth_words;
    if (ekf == nullptr) depth_words = waterBarometer(depths);
    NavigationSource nav;
    nav.track = detail::joinVehicleTrack(std::move(attitude_), ekf ? ekf_[ekf] : std::vector<detail::PositionSample>{},
                                         std::move(depths));
    if (nav.track.empty()) throw FileError("'" + source + "': no ATT record within the span of its position or depth records");
    nav.clock_utc_s = clock_utc_s_;
    nav.geodetic_fixes = std::move(gps_);
    if (!nav.geodetic_fixes.empty()) nav.geodetic_description = "GPS records (Lat, Lng) of " + std::filesystem::path(source).filename().string();
    if (gps_rejected_ > 0) {
      nav.notes.push_back(std::to_string(gps_rejected_) + " GPS records skipped, the first: " + gps_reason_);
    }
    if (!scan.stop_note.empty()) nav.notes.push_back(scan.stop_note);
    if (scan.skipped_bytes > 0) {
      nav.notes.push_back("'" + source + "': " + std::to_string(scan.skipped_bytes) +
                          " bytes between records skipped (no record header of a defined type)");
    }
    if (scan.refused_formats > 0) {
      nav.notes.push_back("'" + source + "': " + std::to_string(scan.refused_formats) +
                          " FMT records refused (an unknown format character, or fields that do not fill the length)");
    }
    nav.description = "ArduPilot dataflash " + std::filesystem::path(source).filename().string() + " (" +
                      detail::vehicleTrackWords("ATT", ekf ? std::string(ekf) + " (core 0)" : "", depth_words) +
                      (clock_utc_s_ ? ", boot time on UTC by GPS" : ", boot time (no GPS fix)") + ")";
    return nav;
  }

 private:
  /// Depths from the barometer in the water: the instance of highest median pressure.
  std::string waterBarometer(std::vector<detail::PositionSample>& depths) {
    double best_median = -1.0;
    int best = -1;
    for (auto& [instance, samples] : pressure_pa_) {
      std::vector<double> values;
      for (const auto& s : samples) values.push_back(s.ned_m.z());
      std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
      if (values[values.size() / 2] > best_median) {
        best_median = values[values.size() / 2];
        best = instance;
      }
    }
    if (best < 0) return "";
    for (detail::PositionSample s : pressure_pa_[best]) {
      s.ned_m.z() = detail::depthOfPressure_m(s.ned_m.z(), options_);
      depths.push_back(s);
    }
    return "BARO instance " + std::to_string(best) + " (pressure)";
  }

  VehicleLogOptions options_;
  std::vector<detail::AttitudeSample> attitude_;
  std::map<std::string, std::vector<detail::PositionSample>> ekf_;
  std::map<int, std::vector<detail::PositionSample>> pressure_pa_;
  std::optional<double> clock_utc_s_;
  std::vector<GeodeticFix> gps_;
  std::size_t gps_rejected_ = 0;
  std::string gps_reason_;
};

}  // namespace

bool isDataflashLog(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xA3 && bytes[1] == 0x95 && bytes[2] == 0x80;
}

NavigationSource parseDataflashNavigation(std::span<const std::uint8_t> bytes, const std::string& source,
                                          const VehicleLogOptions& options) {
  detail::checkVehicleLogOptions(options, "parseDataflashNavigation");
  DataflashNavigation navigation(options);
  const detail::DataflashScan scan =
      detail::scanDataflash(bytes, source, [&](const detail::DataflashRecord& r) { navigation.visit(r); });
  return navigation.finish(source, scan);
}

NavigationSource readDataflashNavigation(const std::string& path, const VehicleLogOptions& options) {
  const std::vector<unsigned char> bytes = detail::readFileBytes(path);
  return parseDataflashNavigation(bytes, path, options);
}

}  // namespace sonarmap
