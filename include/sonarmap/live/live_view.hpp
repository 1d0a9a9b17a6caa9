#pragma once
/// @file live_view.hpp
/// What the page of `sonarmap live --serve` shows, kept by the live session and read by the web
/// server (web_server.hpp): the latest beams (the fan of the current sweep), the map at the
/// vehicle's depth as tiles (map_raster.hpp's TileGrid, drawn on the view's own thread: the voxel
/// layer holding the latest beam's transducer, in a window centred on it; a picture draws again
/// only the tiles the beams shown since the last one may have changed, each PNG-encoded once for
/// every page), the track, the head's settings
/// and the run's status; and how long beams took from their arrival to the page's pixels, from the
/// page's acknowledgements.
///
/// Clock: every time is in seconds on the session's steady clock, counted from the epoch given to
/// the constructor (the session's start): a beam's arrival, a fix's time on the track, an
/// acknowledgement's receipt (now_s()).
/// Frames: the map frame (navigation.hpp: NWU, x north, y west, z up, metres); bearings in the sonar
/// frame (beam.hpp: radians in [0, 2π), clockwise from ahead for a head mounted upright).
/// Threads: every member function is safe from any thread. The session calls the writers (addBeam,
/// mapShows, ...) from the thread that reads the sonar; each costs a lock and a copy of the beam's
/// pooled bins (≤ max_bins), never a map copy: the map's picture is made on the view's raster
/// thread, at most every raster_interval_s and only after the map changed, reading the map in
/// place through the map source (the mapper's shared lock, one tile at a time).
/// Nothing is thrown but what the functions state.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/devices/head_settings.hpp"
#include "sonarmap/live/map_raster.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Where a beam was sent from, as the page draws it.
struct SonarPlacement {
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;  ///< the transducer in the map frame, metres
  /// Direction of bearing 0 on the map's horizontal plane: radians from map +x (north) towards +y
  /// (west), counter-clockwise seen from above.
  double yaw_rad = 0.0;
  /// Whether bearings grow clockwise seen from above (a head mounted upright); false upside down.
  bool clockwise = true;
};

/// The placement of a sonar whose pose in the map is `sonar_to_map` (navigation.hpp's sonarToMap,
/// staticSonarToMap() for a log without navigation: at the origin, bearing 0 north, clockwise).
SonarPlacement placementOf(const Eigen::Isometry3d& sonar_to_map);

/// One beam as the page gets it.
struct LiveBeam {
  std::uint64_t seq = 0;       ///< 0, 1, 2, ... in the order the session added them
  double arrival_s = 0.0;      ///< session clock, seconds
  double bearing_rad = 0.0;    ///< sonar frame
  double bin_length_m = 0.0;   ///< of the bins below: the beam's bin length × the bins pooled into one
  double range_m = 0.0;        ///< the beam's reach: its bin length × its bins, metres
  std::vector<std::uint8_t> intensities;  ///< the beam's bins max-pooled to ≤ LiveViewOptions::max_bins
  SonarPlacement sonar;
};

/// A vehicle position on the track.
struct TrackPoint {
  double time_s = 0.0;                    ///< the navigation's time, seconds
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;  ///< map frame, metres
  double heading_rad = 0.0;               ///< clockwise from north seen from above (NED yaw), radians
};

/// A tile of the latest map picture and the picture that last changed it.
struct TileVersion {
  long i = 0, j = 0;
  std::uint64_t version = 0;
};

/// The latest map picture: tiles of a TileGrid (map_raster.hpp) meeting the window around the
/// sonar, at the layer holding it; each picture draws again only the tiles the map changed in.
struct RasterInfo {
  std::uint64_t version = 0;  ///< 1, 2, ...; 0: none yet
  double cell_m = 0.0;        ///< a pixel's edge, metres (TileGrid::cell_m)
  int tile_px = 0;            ///< pixels along a tile's edge
  std::vector<TileVersion> tiles;  ///< every tile of the picture: those of i0 … i1 × j0 … j1
  long i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  /// The tiles put together (rasterPng, MapRaster's north_m, west_m; cols, rows of its image);
  /// filled by rasterPng only.
  double north_m = 0.0, west_m = 0.0;
  int cols = 0, rows = 0;
  double z_m = 0.0;            ///< map z of the layer cut, metres
  std::uint64_t beams = 0;     ///< beams 0 … beams − 1 were in the map as shown when it was copied
  std::size_t occupied_px = 0, free_px = 0;  ///< over its tiles
  double made_s = 0.0;         ///< session clock when it was published
  double render_s = 0.0;       ///< copying, drawing and encoding it, seconds
  double copy_s = 0.0;         ///< of which in the map source's calls (reading and drawing under the mapper's lock), seconds
  std::size_t tiles_drawn = 0;    ///< tiles drawn for it
  std::size_t tiles_changed = 0;  ///< of which changed (encoded, and sent to the pages)
  std::size_t png_bytes = 0;      ///< of the changed tiles' PNGs
};

/// The run as the page's status panel shows it.
struct LiveStatus {
  double clock_s = 0.0;            ///< now, session clock
  std::uint64_t beams_received = 0;
  double beams_per_s = 0.0;        ///< over the last 2 s
  /// From arrival to the map as shown: the median of the beams shown in the last 2 s, or the wait
  /// of the oldest beam not yet shown when longer; unset before any beam is shown.
  std::optional<double> lag_s;
  std::uint64_t beams_waiting = 0;  ///< received, not yet in the map as shown
  std::size_t sweeps = 0;           ///< sweeps integrated (setSweeps)
  std::string recording_path;
  std::vector<std::string> warnings;  ///< newest last, at most LiveViewOptions::max_warnings
};

/// The head, as the session applied its settings.
struct LiveSettings {
  std::string device;  ///< "Ping360", "Tritech SeaNet head"
  std::vector<std::pair<std::string, std::string>> fields;  ///< name with unit → value ("range_m", "50")
};

/// Percentiles of one latency, seconds.
struct LatencyStats {
  std::size_t count = 0;
  double median_s = 0.0, p95_s = 0.0, max_s = 0.0;
};

/// Beam arrival → pixels on a page, from the pages' acknowledgements (acknowledge): of all pages,
/// each beam counted once, at the first page that drew it, or of one page; and what the map
/// pictures cost.
struct LiveLatencies {
  LatencyStats fan;     ///< arrival → its fan drawn
  LatencyStats map;     ///< arrival → the first map picture including it drawn
  LatencyStats render;  ///< copying the map, rasterising and encoding a picture
  LatencyStats copy;    ///< of which copying the map (the map source's call; the mapper's shared lock is held)
  std::size_t last_png_bytes = 0;
};

/// Where a reader of updates is: what it was sent so far (see LiveView::updateSince).
struct ViewCursor {
  bool started = false;          ///< false: the next update holds everything
  std::uint64_t next_beam = 0;   ///< first beam seq not yet sent
  std::uint64_t track_epoch = 0;
  std::size_t track_sent = 0;
  std::uint64_t settings_version = 0;
  std::uint64_t raster_version = 0;
  std::uint64_t reset_epoch = 0;
  std::uint64_t changes = 0;     ///< LiveView::changes() when the update was made
  /// The view it came from: a cursor of another view (a session started again behind the same
  /// address, a page polling across the restart) starts the reader over.
  std::uint64_t view_id = 0;
};

/// What changed since a cursor.
struct ViewUpdate {
  bool full = false;  ///< holds everything (a new reader, or the map was reset): the reader starts over
  std::vector<std::shared_ptr<const LiveBeam>> beams;  ///< new beams, oldest first, at most fan_beams
  bool track_full = false;        ///< `track` replaces the track (it was thinned), else extends it
  std::vector<TrackPoint> track;
  std::optional<TrackPoint> vehicle;       ///< the latest fix, when any
  std::optional<LiveSettings> settings;    ///< when changed
  std::optional<RasterInfo> raster;        ///< when a newer picture exists
  /// With `raster`: its tiles changed since the cursor's picture (all of them when `full` or the
  /// grid changed), oldest version first.
  std::vector<std::shared_ptr<const MapTile>> tiles;
  LiveStatus status;
  std::size_t fan_beams = 0;  ///< LiveViewOptions::fan_beams
  ViewCursor cursor;          ///< where the reader is after this update
};

struct LiveViewOptions {
  std::size_t fan_beams = 800;  ///< beams kept for the fan (two turns of a Ping360 at 1 gradian)
  std::size_t max_bins = 512;   ///< bins per beam sent to the page (max-pooled), ≥ 16
  /// Least time between the starts of two map pictures, seconds; and at least twice the last
  /// picture's cost, so that the raster thread takes at most half a core. The fan shows each beam
  /// at once; a picture every 0.5 s draws the tiles of a Ping360's 6 to 10 neighbouring beams
  /// together, which cross nearly the same tiles as one (docs/performance.md, "Live on a vehicle").
  double raster_interval_s = 0.5;
  /// Every tile of the window is drawn again at least this often, seconds (and at every sweep
  /// integrated, reset or new layer): what a beam changed is drawn at once from its footprint at
  /// the pose it arrived with, and a pose the mapper corrected later is caught up here.
  double full_redraw_interval_s = 5.0;
  /// Pixels along a map tile's edge (TileGrid::tile_px), ≥ 16: 6.4 m at 0.2 m voxels, a few
  /// tiles along a beam's footprint.
  int tile_px = 32;
  /// Half the edge of the map window drawn, metres; 0: 1.25 × the longest range of the fan's
  /// beams, at least 10 m.
  double raster_half_width_m = 0.0;
  int raster_max_side_px = 2560;  ///< RasterWindow::max_side_px
  double track_spacing_m = 0.25;   ///< a fix joins the track this far from the last point kept,
  double track_turn_rad = 0.087;   ///< or turned this much (5°),
  std::size_t track_max_points = 20000;  ///< beyond which every other point is dropped
  std::size_t max_warnings = 20;
  std::size_t latency_samples = 4096;  ///< latencies kept per kind (the newest)
};

class LiveView {
 public:
  using Clock = std::chrono::steady_clock;
  /// Reads the map as shown in a box (map frame, metres) in place (OnlineMapper::visitShown: the
  /// visitor runs under the mapper's lock); called on the raster thread, once per tile drawn. An
  /// empty box: the visitor only needs the map's resolution.
  using MapSource = std::function<void(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit)>;

  /// @param epoch  the session clock's zero.
  /// @throws ValueError for options out of range (max_bins < 16, fan_beams 0, intervals < 0).
  explicit LiveView(Clock::time_point epoch, LiveViewOptions options = {});
  /// Stops and joins the raster thread.
  ~LiveView();
  LiveView(const LiveView&) = delete;
  LiveView& operator=(const LiveView&) = delete;

  /// Seconds since the epoch, now.
  double now_s() const;
  const LiveViewOptions& options() const { return options_; }

  // --- the session's side ---------------------------------------------------------------------

  /// A beam received at `arrival_s`, sent from `sonar`: kept for the fan (its bins pooled) and
  /// timed. Returns its seq (the count of beams added before it).
  std::uint64_t addBeam(const Beam& beam, double arrival_s, const SonarPlacement& sonar);
  /// The map as shown now holds beams 0 … beams_shown − 1 (or dropped them: a reset map): the
  /// session's beams received minus OnlineMapper::beamsUnshown(). Times their lag and, when it
  /// grew, marks the map changed for the raster thread. Call after each beam given to the mapper.
  void mapShows(std::uint64_t beams_shown);
  void setSweeps(std::size_t sweeps);
  /// A navigation fix (NED, local origin: navigation.hpp); joins the track when it moved or turned
  /// enough (LiveViewOptions), and is the vehicle's pose either way.
  void addNavFix(const NavSample& fix);
  void setSettings(const AppliedSettings& settings);
  void setRecordingPath(std::string path);
  /// A line for the user; one equal to the newest is counted on it ("… (×3)") instead.
  void addWarning(std::string text);

  /// Where the raster thread gets the map: from now on it calls `source` (on its own thread) when
  /// a picture is due. The thread starts at the first call. An empty `source` ends the calls: once
  /// setMapSource({}) returns (it waits for a call in progress), `source` is never called again, so
  /// what it reads (the mapper) may be destroyed before the view.
  void setMapSource(MapSource source);
  /// A copy of the map handed over instead (it replaces a copy not yet drawn); `beams_shown` as
  /// mapShows'. The picture is made on the raster thread.
  void offerMap(OcTree16 map, std::uint64_t beams_shown);
  /// The map was cleared: the picture becomes empty at once (a picture of the old map still being
  /// made is dropped), and a new one is made.
  void mapReset();

  // --- the server's side -----------------------------------------------------------------------

  /// What changed since `cursor`, and the cursor after it.
  ViewUpdate updateSince(const ViewCursor& cursor) const;
  /// A change counter: grows with every change a reader may want.
  std::uint64_t changes() const;
  /// Waits until changes() exceeds `seen`, `timeout` passes or `stop` is requested; returns changes().
  std::uint64_t waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout, std::stop_token stop) const;
  /// The latest picture's tiles put together (composeTiles: cropped to the known pixels plus one)
  /// and its PNG bytes (null before the first); made at the first call after each picture.
  std::pair<RasterInfo, std::shared_ptr<const std::vector<unsigned char>>> rasterPng() const;
  LiveStatus status() const;

  /// A page drew the fans of beams `beam_seqs` and the map pictures `raster_versions`, `held_s`
  /// seconds before this call (its acknowledgement waited that long): each beam's latency is
  /// now_s() − held_s − its arrival, counted at its first acknowledgement. Unknown seqs and
  /// versions (too old, or never made) are ignored. A non-empty `page` (the page's own id) also
  /// counts them for that page alone (latencies(page)); the 16 pages heard from last are kept.
  void acknowledge(std::span<const std::uint64_t> beam_seqs, std::span<const std::uint64_t> raster_versions,
                   double held_s = 0.0, const std::string& page = {});
  /// Of all pages (empty `page`), or of the page `page` alone (zero counts for a page never heard).
  LiveLatencies latencies(const std::string& page = {}) const;
  /// Forgets the latencies measured so far (a measurement starting now).
  void resetLatencies();

 private:
  struct State;
  void rasterLoop(std::stop_token stop);
  void startRasterThread();

  Clock::time_point epoch_;
  std::uint64_t id_;  ///< ViewCursor::view_id
  LiveViewOptions options_;
  std::unique_ptr<State> state_;
  mutable std::mutex mutex_;
  std::mutex source_mutex_;  ///< held while source_ is called or replaced
  MapSource source_;
  mutable std::condition_variable_any changed_;  ///< readers wait on it (waitForChange)
  std::condition_variable_any raster_wake_;      ///< the raster thread waits on it
  std::jthread raster_thread_;  // last: stopped and joined first
};

}  // namespace sonarmap
