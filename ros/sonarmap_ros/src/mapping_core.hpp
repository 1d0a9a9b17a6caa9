#pragma once
/// @file mapping_core.hpp
/// The node's sonarmap side behind plain types, so that the ROS side compiles as C++17: Debian's
/// generated ROS 1 message headers use std::allocator<void>::rebind, which C++20 removed, and the
/// library's headers need C++20. This header uses the standard library and Eigen only.
///
/// MappingCore takes the sonar topic's serialized messages (decoded by their definition:
/// RosSonarDecoder, the bag readers' rules), the vehicle's poses (rosPoseFix) and the mounting
/// (rosMountingToBody), maps them beam by beam (OnlineMapper, `sonarmap map`'s one mapping path),
/// commits the last sweep when the sonar falls silent (OnlineMapper::commitHeld), and gives the map
/// as the data octomap_server's topics carry (MapData). With `slam` the beams and poses go to an
/// OnlineSlam instead (`sonarmap live --slam`'s path: the localizer corrects the poses, the map is
/// built on the corrected track), which gives the correction as ROS's map → odom (mapToOdom). All
/// on one thread.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

namespace sonarmap_ros {

/// How a mapping option's value is given (mapping_option_table.hpp's link kinds).
enum class OptionKind { kNumber, kWord, kBool, kCount };

/// Every mapping option of `sonarmap map` by its Python keyword (optionKeyword: "false_alarm",
/// "volume" for --3d, "beam_width_deg"; a ROS name allows no '-' and no leading digit) and kind.
std::vector<std::pair<std::string, OptionKind>> mappingOptionNames();

/// What the core is built with (node_parameters.hpp reads it from ROS).
struct CoreParameters {
  std::string sonar_topic;
  std::string bearing_unit = "auto";       ///< auto, deg, rad, grad (RosBagOptions)
  std::string bearing_direction = "cw";    ///< cw, ccw
  bool navigation = true;                  ///< false: a fixed sonar at the map's origin
  /// Localization (`map --slam`): the poses are dead reckoning the scans correct, the published map
  /// is in the corrected frame (frame_id, `map`), and the sonar's and the poses' silence ends the
  /// session (OnlineSlam::finish: the final optimisation, the map rebuilt on it).
  bool slam = false;
  /// With slam: how far the poses are trusted (odometry_noise.hpp's classes; `auto` decides from
  /// the poses received by the first sweep, as `live --slam --nav-class auto`).
  std::string nav_class = "auto";
  std::string base_frame = "base_link";    ///< the body frame until a pose names its own
  std::string frame_id = "odom";           ///< the published frame: NED when its name says so, else ENU
  /// Mapping options by keyword (mappingOptionNames), each value as text ("1e-4", "auto", "true", "3").
  std::vector<std::pair<std::string, std::string>> mapping_options;
  std::optional<double> prob_miss, clamp_min, clamp_max;  ///< octomap_server's sensor_model/*
  double occupancy_min_z_m = -1e300, occupancy_max_z_m = 1e300;  ///< markers and cloud band, frame_id's z
  bool free_cells = false;  ///< MapData::free filled (octomap_server's publish_free_space)
  std::size_t bearing_decision_beams = 2000;  ///< auto unit: beams held at most before radians
  /// A beam (a pose) stamped this many seconds before the newest beam (pose) starts a new run (a bag
  /// looped or played again, a new bag): the map and the pose history are cleared.
  double jump_back_s = 1.0;
  /// How long (wall seconds from the first beam) the beams wait for TF to join the sonar's frame to
  /// the body's (a late /tf_static) before the sonar is taken at the body's origin.
  double mounting_wait_s = 10.0;
};

/// A message on the sonar topic whose type has no sonar beam's fields (a publisher of another type).
class NotASonarType : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The map as octomap_server's topics carry it, in frame_id's axes (ENU or NED).
struct MapData {
  double resolution_m = 0.0;
  std::vector<std::int8_t> binary_data, full_data;  ///< octomap_msgs/Octomap data (binary, full)
  struct Cells {
    double edge_m = 0.0;                  ///< the leaves' edge
    std::vector<Eigen::Vector3f> centers; ///< the leaves' centres
  };
  /// The occupied leaves, and with CoreParameters::free_cells the free ones, that reach into the z band
  /// (occupancy_min_z_m … occupancy_max_z_m, as octomap_server takes it), by leaf size, finest last.
  std::vector<Cells> occupied, free;
  /// projected_map: the slice at the vehicle's height, row 0 at the lowest y, 100 occupied, 0 free,
  /// −1 unknown; width 0 when the vehicle is outside the map.
  std::uint32_t grid_width = 0, grid_height = 0;
  double grid_x_m = 0.0, grid_y_m = 0.0, grid_z_m = 0.0;
  std::vector<std::int8_t> grid;
  double stamp_s = 0.0;  ///< the newest beam's time in the map (seconds since the epoch)
};

/// The lag figures (wall seconds).
struct LagReport {
  std::size_t beams = 0, sweeps = 0, beams_without_nav = 0, rejected_messages = 0;
  std::size_t slam_sessions = 0;    ///< with slam: sessions started (a beam after a finished one starts a new map)
  std::size_t slam_scans = 0, slam_matched = 0;  ///< with slam: the localizer's scans and scan matches accepted
  std::size_t runs = 1;            ///< runs begun (a jump back in time starts one: CoreParameters::jump_back_s)
  double queue_delay_max_s = 0.0;  ///< receipt → decoded and given to the mapper
  double map_lag_max_s = 0.0;      ///< receipt → in the committed map
  double last_map_lag_s = -1.0;    ///< of the last beams committed (−1: none yet)
};

class MappingCore {
 public:
  /// The pose of the sonar's frame `sonar_frame` in the vehicle's body frame as TF gives it
  /// (lookupTransform(body, sonar)), or nullopt; the core turns it into the mapper's sonar_to_body
  /// (rosMountingToBody).
  using MountingLookup = std::function<std::optional<Eigen::Isometry3d>(const std::string& sonar_frame)>;
  /// @throws std::runtime_error (sonarmap::ValueError) naming an option that is out of range.
  MappingCore(const CoreParameters& parameters, MountingLookup mounting);
  ~MappingCore();

  /// One message of the sonar topic: its type, definition and serialized bytes (ShapeShifter),
  /// received at `receipt_s` (ROS time: a beam without a header is stamped so) and `receipt_wall_s`.
  /// An automatic bearing unit the field's name does not say is decided as a bag's: degrees at the
  /// first bearing beyond 2π, radians after bearing_decision_beams beams within it or at the
  /// sonar's silence; the beams wait for it, in order.
  /// A message of another type than the sonar's so far replaces its decoder when it has a sonar
  /// beam's fields. The beams also wait, at the start, for TF's mounting (mounting_wait_s).
  /// Returns true when the beam started a new run (its stamp jump_back_s before the newest time seen:
  /// the map and the poses were cleared first).
  /// @throws NotASonarType when the type has no sonar beam's fields (nothing changes); std::runtime_error
  ///         for what mapping a sweep threw.
  bool addSonarMessage(const std::string& type, const std::string& definition, const std::uint8_t* bytes,
                       std::size_t size, double receipt_s, double receipt_wall_s);
  /// One pose of the vehicle (metres, body-to-world quaternion) in `world_frame` (ENU unless its name
  /// says NED), of the body frame `body_frame`; a pose not after the previous one is skipped. Returns
  /// true when it started a new run (as addSonarMessage).
  bool addPose(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
               const std::string& world_frame, const std::string& body_frame);
  /// The sonar silent: held beams decided and mapped, the last sweep committed (commitHeld; with
  /// `navigation_ended` a sweep waiting for a fix too). Returns whether the map changed.
  bool commitAtSilence(bool navigation_ended);
  /// Empties the map (the next beam starts a new mapper, placed from the last pose on; a replay of
  /// the same bag starts a new run by its stamps).
  void reset();
  /// How long the oldest beam received and not yet in the map has waited (wall seconds since its
  /// receipt at `now_wall_s`): for a sweep's end, the bearing unit, the mounting; 0 when none waits.
  double oldestWait_s(double now_wall_s) const;
  /// Whether the first beams wait for TF's mounting (no transform joins the sonar's frame to the
  /// body's yet), and whether the wait ended without one (the sonar at the body's origin).
  bool waitingForMounting() const;
  bool mountingMissing() const;
  /// The sonar's frame (the first beam's header.frame_id).
  const std::string& sonarFrame() const;
  /// Beams received and not yet given to the mapper (waiting for the bearing unit or the mounting).
  std::size_t beamsHeld() const;
  /// Makes the voxels whose centre lies in the box [min_m, max_m] (metres, frame_id's axes) unknown,
  /// as octomap_server's ~clear_bbx; later beams map them again. Returns whether there was a map.
  bool clearBox(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m);
  /// Whether the map changed since the last snapshot().
  bool changed() const { return changed_; }
  /// The map as published; nullopt while an automatic resolution is not set (no sweep yet).
  std::optional<MapData> snapshot();
  /// Writes the map last given by snapshot() as .bt or .ot (by the extension), atomically.
  /// @throws std::runtime_error (sonarmap's FileError, ValueError) naming the path, or saying that the
  ///         map is empty (no voxel known: nothing is written).
  void save(const std::string& path) const;
  const LagReport& lag() const { return lag_; }
  /// ROS's map → odom (REP 105) from slam's latest correction: the pose of the poses' world frame
  /// (odom; its axes ENU unless its name says NED) in frame_id's axes, metres; stamped with the
  /// newest pose's time (seconds). nullopt without slam, without navigation or before the first scan.
  struct MapToOdom {
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    std::string odom_frame;
    double stamp_s = 0.0;
  };
  std::optional<MapToOdom> mapToOdom() const;
  /// The body frame of the poses (the last addPose's), for the mounting.
  const std::string& bodyFrame() const { return body_frame_; }

 private:
  /// Starts the mapper (or with slam the OnlineSlam) at the first beam: options, mounting, the
  /// poses received before it.
  void start();
  /// Gives the beams held to the mapper (started at the first: options, mounting), bearings set.
  void feedHeld();
  /// Notes the lag of the beams the mapper committed since the last call.
  void noteLag();
  /// A stamp of a beam or a `pose`: a new run (newRun) when it is jump_back_s before the newest of
  /// its stream (beams, poses).
  bool noteStamp(double time_s, bool pose);
  /// Clears the map, the beams held, the pose history and the mounting (looked up again): what came
  /// before a jump back in time.
  void newRun();
  /// Whether the mounting is known or given up (looked up again while mounting_wait_s lasts).
  bool mountingSettled(double now_wall_s);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  LagReport lag_;
  std::string body_frame_;
  bool changed_ = false;
};

}  // namespace sonarmap_ros
