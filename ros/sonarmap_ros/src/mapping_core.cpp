/// @file mapping_core.cpp
/// The node's sonarmap side (mapping_core.hpp).

#include "mapping_core.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <limits>

#include "core_internal.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ros_sonar_message.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/io/octomap_full.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/slam/odometry_noise.hpp"
#include "sonarmap/slam/online_slam.hpp"

namespace sonarmap_ros {

struct MappingCore::Impl {
  CoreParameters parameters;
  MountingLookup mounting;
  sonarmap::MapFrame frame = sonarmap::MapFrame::kEnu;
  std::optional<sonarmap::RosSonarDecoder> decoder;
  std::string decoder_type;  ///< the message type the decoder reads
  std::string sonar_frame;
  std::optional<sonarmap::NominalBeam> nominal_beam;
  struct Held {
    sonarmap::RosSonarMessage message;
    double receipt_wall_s = 0.0;
  };
  std::deque<Held> held;  ///< beams waiting for an automatic bearing unit
  double largest_bearing = 0.0;
  std::unique_ptr<sonarmap::OnlineMapper> mapper;  ///< without slam
  std::unique_ptr<sonarmap::OnlineSlam> slam;      ///< with slam
  bool slam_finished = false;                      ///< slam's session ended at a silence
  std::vector<sonarmap::NavSample> early_fixes;  ///< before the mapper starts
  std::optional<sonarmap::NavSample> last_fix;
  std::string world_frame;  ///< the poses' world frame (the last addPose's)

  bool started() const { return mapper || slam; }
  /// The mapper whose map is published (slam's current one; not kept: a rebuild swaps it).
  sonarmap::OnlineMapper& active() { return slam ? slam->mapper() : *mapper; }
  std::size_t beamsPending() const { return slam ? slam->beamsPending() : mapper->beamsPending(); }
  void addNavFix(const sonarmap::NavSample& fix) {
    if (slam) {
      slam->addNavFix(fix);
    } else {
      mapper->addNavFix(fix);
    }
  }
  std::deque<double> receipts_wall_s;  ///< of the beams given to the mapper and not yet in its map
  double newest_time_s = 0.0;          ///< the newest beam's time
  /// The run's clocks: the newest stamp of a beam [0] and of a pose [1] (a stamp jump_back_s before
  /// its stream's: a new run). Each stream by itself: TF's poses may come late, from its history.
  double run_clock_s[2] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  std::optional<Eigen::Isometry3d> mounting_found;  ///< TF's sonar-in-body once found
  bool mounting_given_up = false;                    ///< mounting_wait_s passed without it
  double first_beam_wall_s = -1.0;                   ///< the first beam's receipt (the mounting's wait)
  double empty_resolution_m = 0.1;     ///< an empty map's after reset, before any sweep
  std::optional<sonarmap::OcTree16> published;
};

MappingCore::MappingCore(const CoreParameters& parameters, MountingLookup mounting) : impl_(std::make_unique<Impl>()) {
  impl_->parameters = parameters;
  impl_->mounting = std::move(mounting);
  body_frame_ = parameters.base_frame;
  impl_->frame = sonarmap::rosFrameIsNed(parameters.frame_id) ? sonarmap::MapFrame::kNed : sonarmap::MapFrame::kEnu;
  sonarmap::parseBearingUnit(parameters.bearing_unit);  // the options are checked now, not at the first beam
  sonarmap::parseBearingDirection(parameters.bearing_direction);
  coreMapperOptions(parameters, sonarmap::nominalBeam(sonarmap::LogFormat::kRosBag));
  if (parameters.nav_class != "auto") sonarmap::odometryNoiseOf(parameters.nav_class);  // throws naming the classes
}

MappingCore::~MappingCore() = default;

namespace {

/// Beams committed since the last call (all but `pending` of those received): their receipts
/// leave `receipts`; returns the newest one's lag, or −1.
double noteCommitted(std::size_t pending, std::deque<double>& receipts, double now_wall_s) {
  if (receipts.size() <= pending) return -1.0;
  const std::size_t committed = receipts.size() - pending;
  const double newest = receipts[committed - 1];
  receipts.erase(receipts.begin(), receipts.begin() + static_cast<std::ptrdiff_t>(committed));
  return now_wall_s - newest;
}

double wallNow_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

bool MappingCore::addSonarMessage(const std::string& type, const std::string& definition, const std::uint8_t* bytes,
                                  std::size_t size, double receipt_s, double receipt_wall_s) {
  Impl& d = *impl_;
  if (!d.decoder || type != d.decoder_type) {
    // a publisher of another type: its decoder replaces the sonar's only when it reads a beam
    sonarmap::RosBagOptions options;
    options.sonar_topic = d.parameters.sonar_topic;
    options.bearing_unit = sonarmap::parseBearingUnit(d.parameters.bearing_unit);
    options.bearing_direction = sonarmap::parseBearingDirection(d.parameters.bearing_direction);
    try {
      d.decoder.emplace(type, definition, options);
    } catch (const sonarmap::ValueError& error) {
      throw NotASonarType(error.what());
    }
    d.decoder_type = type;
  }
  sonarmap::RosSonarMessage message;
  try {
    message = d.decoder->decode(std::span<const std::uint8_t>(bytes, size), receipt_s);
  } catch (const sonarmap::Error&) {
    ++lag_.rejected_messages;
    return false;
  }
  const bool new_run = noteStamp(message.beam.time_s, false);
  if (d.first_beam_wall_s < 0.0) d.first_beam_wall_s = receipt_wall_s;
  if (lag_.beams == 0 && d.held.empty()) {
    d.sonar_frame = message.frame_id;
    d.nominal_beam = message.nominal_beam;
  }
  d.largest_bearing = std::max(d.largest_bearing, std::abs(message.bearing));
  d.held.push_back({std::move(message), receipt_wall_s});
  if (!d.decoder->unitDecided() && !sonarmap::RosSonarDecoder::beyondRadians(d.largest_bearing) &&
      d.held.size() < d.parameters.bearing_decision_beams) {
    return new_run;  // the unit is not known yet: the beams wait (mapping_core.hpp; a bag's rule)
  }
  if (!d.decoder->unitDecided()) d.decoder->decideUnit(d.largest_bearing);
  feedHeld();
  return new_run;
}

bool MappingCore::noteStamp(double time_s, bool pose) {
  Impl& d = *impl_;
  double& clock = d.run_clock_s[pose ? 1 : 0];
  if (time_s < clock - d.parameters.jump_back_s) {
    newRun();
    d.run_clock_s[0] = d.run_clock_s[1] = -std::numeric_limits<double>::infinity();
    clock = time_s;
    ++lag_.runs;
    return true;
  }
  clock = std::max(clock, time_s);
  return false;
}

void MappingCore::newRun() {
  reset();
  Impl& d = *impl_;
  d.early_fixes.clear();
  d.last_fix.reset();
  d.newest_time_s = 0.0;
  // a new bag may mount the sonar otherwise: looked up again (its /tf_static came with it)
  d.mounting_found.reset();
  d.mounting_given_up = false;
  d.first_beam_wall_s = -1.0;
}

bool MappingCore::mountingSettled(double now_wall_s) {
  Impl& d = *impl_;
  if (!d.parameters.navigation || d.mounting_found || d.mounting_given_up) return true;
  if (!d.sonar_frame.empty()) d.mounting_found = d.mounting(d.sonar_frame);
  // no frame to look up, or TF has not joined the frames in mounting_wait_s: the body's origin
  if (!d.mounting_found && (d.sonar_frame.empty() || now_wall_s - d.first_beam_wall_s >= d.parameters.mounting_wait_s)) {
    d.mounting_given_up = true;
  }
  return d.mounting_found || d.mounting_given_up;
}

double MappingCore::oldestWait_s(double now_wall_s) const {
  const Impl& d = *impl_;
  double oldest = std::numeric_limits<double>::infinity();
  if (!d.held.empty()) oldest = d.held.front().receipt_wall_s;
  if (!d.receipts_wall_s.empty()) oldest = std::min(oldest, d.receipts_wall_s.front());
  return std::isfinite(oldest) ? std::max(0.0, now_wall_s - oldest) : 0.0;
}

bool MappingCore::waitingForMounting() const {
  const Impl& d = *impl_;
  return d.parameters.navigation && !d.started() && !d.held.empty() && !d.mounting_found && !d.mounting_given_up;
}

bool MappingCore::mountingMissing() const { return impl_->mounting_given_up; }

const std::string& MappingCore::sonarFrame() const { return impl_->sonar_frame; }

std::size_t MappingCore::beamsHeld() const { return impl_->held.size(); }

void MappingCore::feedHeld() {
  Impl& d = *impl_;
  if (d.held.empty()) return;
  if (d.slam_finished) {
    // A beam after the session ended (a bag played again, a new dive): a new session, a new map.
    d.slam.reset();
    d.slam_finished = false;
    if (d.last_fix) d.early_fixes.push_back(*d.last_fix);
  }
  const double now_s = wallNow_s();
  if (!d.started()) {
    if (!mountingSettled(now_s)) {
      return;  // the beams wait for TF's mounting (a late /tf_static)
    }
    start();
  }
  while (!d.held.empty()) {
    Impl::Held held = std::move(d.held.front());
    d.held.pop_front();
    held.message.beam.bearing_rad = d.decoder->bearingRad(held.message.bearing);
    lag_.queue_delay_max_s = std::max(lag_.queue_delay_max_s, now_s - held.receipt_wall_s);
    d.newest_time_s = held.message.beam.time_s;
    d.receipts_wall_s.push_back(held.receipt_wall_s);
    ++lag_.beams;
    if (d.slam) {
      d.slam->addBeam(std::move(held.message.beam));
    } else {
      d.mapper->addBeam(std::move(held.message.beam));
    }
  }
  noteLag();
}

void MappingCore::start() {
  Impl& d = *impl_;
  sonarmap::SonarLog header;
  header.nominal_beam = d.nominal_beam;
  const sonarmap::MapperOptions options =
      coreMapperOptions(d.parameters, sonarmap::nominalBeam(sonarmap::LogFormat::kRosBag, header));
  Eigen::Isometry3d mounting = Eigen::Isometry3d::Identity();
  if (d.parameters.navigation) {
    // without TF's mounting: the sonar at the body's origin, its frame the body's (REP 103 FLU)
    if (d.mounting_found) mounting = sonarmap::rosMountingToBody(*d.mounting_found, body_frame_, d.sonar_frame);
  }
  if (!d.parameters.slam) {
    d.mapper = d.parameters.navigation ? std::make_unique<sonarmap::OnlineMapper>(options, mounting)
                                       : std::make_unique<sonarmap::OnlineMapper>(options);
  } else if (!d.parameters.navigation) {
    d.slam = std::make_unique<sonarmap::OnlineSlam>(options, mounting, false);
  } else {
    // The localization's options decided at the first sweep from the poses received by then, as
    // `live --slam` decides them from a stream (`map --slam` from the whole log's).
    const std::string nav_class = d.parameters.nav_class;
    d.slam = std::make_unique<sonarmap::OnlineSlam>(options, mounting, [nav_class](const sonarmap::NavTrack& fixes) {
      sonarmap::SlamOptions slam;
      slam.forming.odometry =
          sonarmap::odometryNoiseOf(nav_class == "auto" ? sonarmap::navigationClassOf(fixes) : nav_class);
      return sonarmap::withNavigationPeriod(slam, fixes);
    });
  }
  if (d.slam) ++lag_.slam_sessions;
  if (d.parameters.navigation) {
    for (const sonarmap::NavSample& fix : d.early_fixes) d.addNavFix(fix);
  }
  d.early_fixes.clear();
}

void MappingCore::noteLag() {
  Impl& d = *impl_;
  if (d.slam) {
    lag_.slam_scans = d.slam->localizer().report().scans;
    lag_.slam_matched = d.slam->localizer().report().matches_accepted;
  }
  if (const double lag_s = noteCommitted(d.beamsPending(), d.receipts_wall_s, wallNow_s()); lag_s >= 0.0) {
    lag_.last_map_lag_s = lag_s;
    lag_.map_lag_max_s = std::max(lag_.map_lag_max_s, lag_s);
    changed_ = true;
  }
}

bool MappingCore::addPose(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
                          const std::string& world_frame, const std::string& body_frame) {
  Impl& d = *impl_;
  const bool new_run = noteStamp(time_s, true);
  const sonarmap::NavSample fix = sonarmap::rosPoseFix(time_s, position_m, orientation, world_frame);
  if (d.last_fix && !(fix.time_s > d.last_fix->time_s)) return new_run;  // skipped, as a bag's
  if (!d.last_fix) body_frame_ = body_frame;
  d.last_fix = fix;
  d.world_frame = world_frame;
  if (!d.parameters.navigation) return new_run;
  if (!d.started() || d.slam_finished) {
    d.early_fixes.push_back(fix);
    return new_run;
  }
  d.addNavFix(fix);
  noteLag();
  return new_run;
}

bool MappingCore::commitAtSilence(bool navigation_ended) {
  Impl& d = *impl_;
  // The whole stream seen: an undecided unit is decided on every bearing, as a bag's.
  if (d.decoder && !d.decoder->unitDecided() && !d.held.empty()) d.decoder->decideUnit(d.largest_bearing);
  // and the mounting's wait ends: TF had the time it had
  if (!d.held.empty() && !mountingSettled(wallNow_s())) d.mounting_given_up = true;
  feedHeld();
  if (!d.started()) return false;
  const std::size_t sweeps = d.active().sweepsIntegrated();
  const bool ended = navigation_ended || !d.parameters.navigation;
  if (!d.slam) {
    d.mapper->commitHeld(ended);
  } else if (ended && !d.slam_finished) {
    // slam's last sweep is its last scan: the session ends (the final optimisation, the map
    // rebuilt on it: `map --slam`'s map of the same beams and poses).
    d.slam->finish();
    d.slam_finished = true;
  }
  noteLag();
  const sonarmap::MappingStats stats = d.active().statsSnapshot();
  lag_.sweeps = d.active().sweepsIntegrated();
  lag_.beams_without_nav = stats.beams_without_nav;
  if (lag_.sweeps != sweeps) changed_ = true;
  return lag_.sweeps != sweeps;
}

void MappingCore::reset() {
  Impl& d = *impl_;
  if (d.mapper && d.mapper->optionsSnapshot().resolution_m) d.empty_resolution_m = *d.mapper->optionsSnapshot().resolution_m;
  if (d.slam && d.slam->mapper().optionsSnapshot().resolution_m) {
    d.empty_resolution_m = *d.slam->mapper().optionsSnapshot().resolution_m;
  }
  d.mapper.reset();
  d.slam.reset();
  d.slam_finished = false;
  d.held.clear();
  d.receipts_wall_s.clear();
  d.early_fixes.clear();
  if (d.last_fix) d.early_fixes.push_back(*d.last_fix);
  changed_ = true;
}

namespace {

/// Copies into `out` the part of the cube (`key`, `depth`) of log-odds `log_odds` whose finest voxels'
/// centres lie outside [lo, hi] (metres, the map's frame), splitting the cube where the box cuts it.
void copyOutside(sonarmap::OcTree16& out, const sonarmap::Key16& key, int depth, float log_odds, const Eigen::Vector3d& lo,
                 const Eigen::Vector3d& hi) {
  const double res = out.resolution_m(), offset = sonarmap::KeyCoder<16>::offset();
  const long edge = 1L << (16 - depth);
  bool disjoint = false, inside = true;
  for (int axis = 0; axis < 3; ++axis) {
    // the centres of the cube's voxels along the axis: first and last
    const double first = (key[static_cast<std::size_t>(axis)] - offset + 0.5) * res;
    const double last = first + static_cast<double>(edge - 1) * res;
    if (last < lo[axis] || first > hi[axis]) disjoint = true;
    if (first < lo[axis] || last > hi[axis]) inside = false;
  }
  if (disjoint) {
    out.updateCube(key, depth, log_odds);
    return;
  }
  if (inside) return;
  const long half = edge / 2;  // depth < 16 here: a finest voxel is disjoint or inside
  for (int child = 0; child < 8; ++child) {
    sonarmap::Key16 sub = key;
    for (int axis = 0; axis < 3; ++axis) {
      if ((child >> axis) & 1) sub[static_cast<std::size_t>(axis)] = static_cast<sonarmap::Key16::Index>(sub[static_cast<std::size_t>(axis)] + half);
    }
    copyOutside(out, sub, depth + 1, log_odds, lo, hi);
  }
}

}  // namespace

bool MappingCore::clearBox(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m) {
  Impl& d = *impl_;
  if (!d.started() || !d.active().optionsSnapshot().resolution_m) return false;
  const Eigen::Matrix3d to_nwu = sonarmap::nwuToMapFrame(d.frame).transpose();
  const Eigen::Vector3d a = to_nwu * min_m, b = to_nwu * max_m;
  const Eigen::Vector3d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
  // the feeding thread: this one (with slam, a later rebuild maps the cleared sweeps again)
  sonarmap::OcTree16& map = d.active().mapper().map();
  sonarmap::OcTree16 out(map.resolution_m(), map.options());
  map.forEachLeaf([&](const sonarmap::LeafView<16>& leaf) { copyOutside(out, leaf.key, leaf.depth, leaf.log_odds, lo, hi); });
  out.updateInnerOccupancy();
  map = std::move(out);
  changed_ = true;
  return true;
}

std::optional<MapData> MappingCore::snapshot() {
  Impl& d = *impl_;
  changed_ = false;
  if (d.started() && !d.active().optionsSnapshot().resolution_m) return std::nullopt;  // auto: none before a sweep
  sonarmap::OcTree16 map = d.started() ? sonarmap::mapInFrame(d.active().mapSnapshot(), d.frame)
                                    : sonarmap::OcTree16(d.empty_resolution_m, coreMapperOptions(d.parameters,
                                          sonarmap::nominalBeam(sonarmap::LogFormat::kRosBag)).octree);
  double z_m = 0.0;  // the vehicle's height in frame_id (the sonar's plane without navigation)
  if (d.last_fix && d.parameters.navigation) {
    const Eigen::Vector3d& ned = d.last_fix->position_ned_m;
    z_m = (sonarmap::nwuToMapFrame(d.frame) * Eigen::Vector3d(ned.x(), -ned.y(), -ned.z())).z();
  }
  MapData data = mapData(map, d.parameters, z_m);
  data.stamp_s = d.newest_time_s;
  d.published = std::move(map);
  return data;
}

void MappingCore::save(const std::string& path) const {
  const Impl& d = *impl_;
  if (!d.published) throw sonarmap::ValueError("~save_map: no map published yet");
  if (d.published->empty()) {
    throw sonarmap::ValueError("~save_map: the map is empty (" + std::to_string(lag_.beams) + " beams mapped, " +
                               std::to_string(lag_.beams_without_nav) + " of them without navigation): " + path +
                               " not written");
  }
  const std::vector<std::string> comments{sonarmap::mapFrameComment(d.frame)};
  if (path.ends_with(".ot")) {
    sonarmap::writeFullFile(*d.published, path, comments);
  } else if (path.ends_with(".bt")) {
    sonarmap::writeBinaryFile(*d.published, path, comments);
  } else {
    throw sonarmap::ValueError("~save_path " + path + ": .bt or .ot is needed");
  }
}

std::optional<MappingCore::MapToOdom> MappingCore::mapToOdom() const {
  const Impl& d = *impl_;
  if (!d.slam || !d.parameters.navigation || !d.last_fix || d.slam->localizer().scans().empty()) return std::nullopt;
  // NED's axes in a frame's: NED → NWU, then NWU → the frame's (ENU, or NED when its name says so)
  const Eigen::Matrix3d ned_to_nwu = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  const Eigen::Matrix3d to_map = sonarmap::nwuToMapFrame(d.frame) * ned_to_nwu;
  const sonarmap::MapFrame odom_kind = sonarmap::rosFrameIsNed(d.world_frame) ? sonarmap::MapFrame::kNed : sonarmap::MapFrame::kEnu;
  const Eigen::Matrix3d to_odom = sonarmap::nwuToMapFrame(odom_kind) * ned_to_nwu;
  const sonarmap::Pose2& correction = d.slam->correction();  // NED: corrected = correction ∘ dead reckoning
  const Eigen::Matrix3d rotation_ned = Eigen::AngleAxisd(correction.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  MapToOdom out;
  out.transform.linear() = to_map * rotation_ned * to_odom.transpose();
  out.transform.translation() = to_map * Eigen::Vector3d(correction.x_m, correction.y_m, 0.0);
  out.odom_frame = d.world_frame;
  out.stamp_s = d.last_fix->time_s;
  return out;
}

}  // namespace sonarmap_ros
