#include "sonarmap/live/live_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "map_tiles.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/live/map_raster.hpp"
#include "sonarmap/sonar/png_writer.hpp"

namespace sonarmap {
namespace {

/// Beams whose arrival is kept for timing: 11 minutes of a Ping360 at 12 beams a second.
constexpr std::size_t kArrivalsKept = 8192;
/// Map pictures whose beam count is kept for the pages' acknowledgements.
constexpr std::size_t kRastersKept = 64;
/// The window of the beam rate and of the lag's median, seconds.
constexpr double kRateWindow_s = 2.0;

LatencyStats statsOf(std::deque<double> samples) {
  LatencyStats stats;
  stats.count = samples.size();
  if (samples.empty()) return stats;
  std::sort(samples.begin(), samples.end());
  const auto at = [&](double q) {
    return samples[std::min(samples.size() - 1, static_cast<std::size_t>(q * static_cast<double>(samples.size())))];
  };
  stats.median_s = at(0.5);
  stats.p95_s = at(0.95);
  stats.max_s = samples.back();
  return stats;
}

void pushBounded(std::deque<double>& samples, double value, std::size_t cap) {
  samples.push_back(value);
  while (samples.size() > cap) samples.pop_front();
}

double wrappedAngle(double radians) { return std::remainder(radians, 2.0 * std::numbers::pi); }

/// How far the mapper may place a beam from where it arrived: a beam after the last fix is shown at
/// that fix's pose, held for up to 1 s (OnlineIntegration::kProvisionalBeams), and a small vehicle
/// moves under 1 m/s; metres.
constexpr double kPoseSlack_m = 1.0;

/// Half the angle around a beam's bearing that its map update may reach, radians: wider than any
/// MSIS's horizontal beam (Ping360 2°, Micron 3°, Imagenex 881 2.4°: their makers' −3 dB widths).
constexpr double kFootprintHalfAngle_rad = 0.1;

/// Beams' footprints kept for the next picture; beyond, it draws every tile.
constexpr std::size_t kFootprintsKept = 256;

/// The part of the map (x, y) a beam may change: the segment from its sonar to its reach, widened
/// by kFootprintHalfAngle_rad at that reach and by the pose slack.
live::BeamFootprint footprintOf(const LiveBeam& beam) {
  const double alpha = beam.sonar.yaw_rad + (beam.sonar.clockwise ? -beam.bearing_rad : beam.bearing_rad);
  live::BeamFootprint footprint;
  footprint.from_m = {beam.sonar.x_m, beam.sonar.y_m};
  footprint.to_m = footprint.from_m + beam.range_m * Eigen::Vector2d(std::cos(alpha), std::sin(alpha));
  footprint.margin_m = beam.range_m * std::sin(kFootprintHalfAngle_rad) + kPoseSlack_m;
  return footprint;
}

/// The map source has been removed (LiveView::setMapSource({})): no picture.
struct NoMapSource {};

}  // namespace

SonarPlacement placementOf(const Eigen::Isometry3d& sonar_to_map) {
  SonarPlacement placement;
  const Eigen::Vector3d position = sonar_to_map.translation();
  placement.x_m = position.x();
  placement.y_m = position.y();
  placement.z_m = position.z();
  const Eigen::Vector3d ahead = sonar_to_map.linear() * Eigen::Vector3d::UnitX();
  placement.yaw_rad = std::hypot(ahead.x(), ahead.y()) > 1e-9 ? std::atan2(ahead.y(), ahead.x()) : 0.0;
  placement.clockwise = (sonar_to_map.linear() * Eigen::Vector3d::UnitZ()).z() < 0.0;
  return placement;
}

struct LiveView::State {
  std::uint64_t changes = 0;
  // Beams: the fan's, and every recent arrival (seq = beams − arrivals.size() + index).
  struct Arrival {
    double arrival_s = 0.0;
    bool fan_drawn = false;
  };
  std::deque<std::shared_ptr<const LiveBeam>> fan;
  std::deque<Arrival> arrivals;
  std::uint64_t beams = 0;
  std::optional<double> first_arrival_s;
  std::optional<SonarPlacement> sonar;  ///< the latest beam's
  double range_m = 0.0;                 ///< the latest beam's reach
  // The map as shown.
  std::uint64_t shown = 0;
  std::deque<std::pair<double, double>> shown_lags;  ///< (when shown, lag), the last kRateWindow_s
  std::optional<double> last_lag_s;
  std::size_t sweeps = 0;
  // Track and head.
  std::vector<TrackPoint> track;
  std::uint64_t track_epoch = 0;
  std::optional<TrackPoint> vehicle;
  LiveSettings settings;
  std::uint64_t settings_version = 0;
  std::string recording_path;
  std::deque<std::string> warnings;
  std::string last_warning;
  std::size_t last_warning_repeats = 0;
  // Map pictures.
  RasterInfo raster;
  std::vector<std::shared_ptr<const MapTile>> tiles;  ///< the latest picture's, by (i, j)
  std::deque<std::pair<std::uint64_t, std::uint64_t>> raster_beams;  ///< (version, beams), newest last
  std::uint64_t reset_epoch = 0;
  bool map_dirty = false;
  bool redraw_all = true;                    ///< the next picture draws every tile
  bool forget_tiles = false;                 ///< the map was reset: the raster thread's tiles are stale
  std::vector<live::BeamFootprint> changed;  ///< the beams shown since the last picture
  double last_full_s = -std::numeric_limits<double>::infinity();
  live::MapTiles map_tiles;             ///< the raster thread's own (outside the lock)
  // The tiles put together for rasterPng, made at its first call after each picture.
  std::uint64_t composed_version = 0;
  RasterInfo composed_info;
  std::shared_ptr<const std::vector<unsigned char>> composed_png;
  bool has_source = false;  ///< setMapSource was given a source
  std::optional<OcTree16> offered;
  std::uint64_t offered_beams = 0;
  double last_raster_start_s = -std::numeric_limits<double>::infinity();
  double last_render_s = 0.0;  ///< the last picture's cost
  // Latencies.
  std::deque<double> fan_latencies, map_latencies, render_times, copy_times;
  std::uint64_t map_drawn_beams = 0;  ///< beams below it were counted in map_latencies
  /// One page's own: the beams it drew, each counted once by it.
  struct PageLatencies {
    std::deque<double> fan, map;
    std::uint64_t fan_drawn_from = 0;   ///< its acknowledged beams are counted from here on
    std::uint64_t map_drawn_beams = 0;
    double heard_s = 0.0;
  };
  std::map<std::string, PageLatencies> pages;
  std::uint64_t timed_from = 0;       ///< beams below it are not timed (resetLatencies)

  std::optional<double> arrivalOf(std::uint64_t seq) const {
    const std::uint64_t first = beams - arrivals.size();
    if (seq < first || seq >= beams) return std::nullopt;
    return arrivals[seq - first].arrival_s;
  }

  void warn(std::string text, std::size_t max_warnings) {
    if (!warnings.empty() && text == last_warning) {
      warnings.back() = text + " (x" + std::to_string(++last_warning_repeats) + ")";
    } else {
      last_warning = text;
      last_warning_repeats = 1;
      warnings.push_back(std::move(text));
      while (warnings.size() > max_warnings) warnings.pop_front();
    }
    ++changes;
  }

  /// Publishes a picture, made for `beams` beams, as version `version`.
  void publish(const live::TilePicture& made, std::uint64_t version, std::uint64_t made_beams, double now_s,
               double render_s) {
    RasterInfo info;
    info.version = version;
    info.cell_m = made.grid.cell_m();
    info.tile_px = made.grid.tile_px;
    info.i0 = made.i0, info.i1 = made.i1, info.j0 = made.j0, info.j1 = made.j1;
    info.z_m = made.z_m;
    info.beams = made_beams;
    for (const auto& tile : made.tiles) {
      info.tiles.push_back({tile->i, tile->j, tile->version});
      info.occupied_px += tile->occupied_px;
      info.free_px += tile->free_px;
    }
    info.made_s = now_s;
    info.render_s = render_s;
    info.copy_s = made.copy_s;
    info.tiles_drawn = made.drawn;
    info.tiles_changed = made.changed;
    info.png_bytes = made.png_bytes;
    raster = std::move(info);
    tiles = made.tiles;
    raster_beams.emplace_back(version, made_beams);
    while (raster_beams.size() > kRastersKept) raster_beams.pop_front();
    ++changes;
  }
};

LiveView::LiveView(Clock::time_point epoch, LiveViewOptions options)
    : epoch_(epoch),
      id_(static_cast<std::uint64_t>(Clock::now().time_since_epoch().count()) ^ reinterpret_cast<std::uintptr_t>(this)),
      options_(options),
      state_(std::make_unique<State>()) {
  if (options_.max_bins < 16) throw ValueError("live view: max_bins must be >= 16");
  if (options_.fan_beams == 0) throw ValueError("live view: fan_beams must be > 0");
  if (!(options_.raster_interval_s >= 0.0) || !(options_.raster_half_width_m >= 0.0) ||
      !(options_.track_spacing_m >= 0.0) || !(options_.track_turn_rad >= 0.0)) {
    throw ValueError("live view: intervals, widths and spacings must be >= 0");
  }
  if (options_.raster_max_side_px < 16) throw ValueError("live view: raster_max_side_px must be >= 16");
  options_.track_max_points = std::max<std::size_t>(options_.track_max_points, 2);
  options_.latency_samples = std::max<std::size_t>(options_.latency_samples, 1);
  if (options_.tile_px < 16) throw ValueError("live view: tile_px must be >= 16");
  if (!(options_.full_redraw_interval_s >= 0.0)) throw ValueError("live view: full_redraw_interval_s must be >= 0");
  state_->map_tiles = live::MapTiles(options_.tile_px);
}

LiveView::~LiveView() {
  raster_thread_.request_stop();
  raster_wake_.notify_all();
  if (raster_thread_.joinable()) raster_thread_.join();
}

double LiveView::now_s() const { return std::chrono::duration<double>(Clock::now() - epoch_).count(); }

std::uint64_t LiveView::addBeam(const Beam& beam, double arrival_s, const SonarPlacement& sonar) {
  auto pooled = std::make_shared<LiveBeam>();
  const std::size_t bins = beam.intensities.size();
  const std::size_t per_bin = std::max<std::size_t>(1, (bins + options_.max_bins - 1) / options_.max_bins);
  pooled->intensities.resize((bins + per_bin - 1) / per_bin);
  for (std::size_t i = 0; i < bins; ++i) {
    std::uint8_t& out = pooled->intensities[i / per_bin];
    out = std::max(out, beam.intensities[i]);
  }
  pooled->arrival_s = arrival_s;
  pooled->bearing_rad = beam.bearing_rad;
  pooled->bin_length_m = beam.bin_length_m * static_cast<double>(per_bin);
  pooled->range_m = beam.bin_length_m * static_cast<double>(bins);
  pooled->sonar = sonar;
  std::lock_guard lock(mutex_);
  State& s = *state_;
  pooled->seq = s.beams;
  s.fan.push_back(std::move(pooled));
  while (s.fan.size() > options_.fan_beams) s.fan.pop_front();
  s.arrivals.push_back({arrival_s, false});
  if (s.arrivals.size() > kArrivalsKept) s.arrivals.pop_front();
  if (!s.first_arrival_s) s.first_arrival_s = arrival_s;
  s.sonar = sonar;
  s.range_m = beam.bin_length_m * static_cast<double>(bins);
  ++s.changes;
  changed_.notify_all();
  return s.beams++;
}

void LiveView::mapShows(std::uint64_t beams_shown) {
  std::lock_guard lock(mutex_);
  State& s = *state_;
  beams_shown = std::min(beams_shown, s.beams);
  if (beams_shown <= s.shown) return;
  const double now = now_s();
  const std::uint64_t first_in_fan = s.fan.empty() ? s.beams : s.fan.front()->seq;
  for (std::uint64_t seq = s.shown; seq < beams_shown; ++seq) {
    if (const std::optional<double> arrival = s.arrivalOf(seq)) s.shown_lags.emplace_back(now, now - *arrival);
    if (seq < first_in_fan || s.changed.size() >= kFootprintsKept) {
      s.redraw_all = true;  // its footprint is no longer known, or too many to test
      s.changed.clear();
    } else if (!s.redraw_all) {
      s.changed.push_back(footprintOf(*s.fan[seq - first_in_fan]));
    }
  }
  while (!s.shown_lags.empty() && s.shown_lags.front().first < now - kRateWindow_s) s.shown_lags.pop_front();
  if (!s.shown_lags.empty()) s.last_lag_s = s.shown_lags.back().second;
  s.shown = beams_shown;
  s.map_dirty = true;
  ++s.changes;
  raster_wake_.notify_all();
  changed_.notify_all();
}

void LiveView::setSweeps(std::size_t sweeps) {
  std::lock_guard lock(mutex_);
  if (state_->sweeps == sweeps) return;
  state_->sweeps = sweeps;
  state_->map_dirty = true;  // a committed sweep replaces its provisional beams: every tile is drawn again
  state_->redraw_all = true;
  ++state_->changes;
  raster_wake_.notify_all();
  changed_.notify_all();
}

void LiveView::addNavFix(const NavSample& fix) {
  const TrackPoint point{fix.time_s, fix.position_ned_m.x(), -fix.position_ned_m.y(), -fix.position_ned_m.z(),
                         fix.yaw_rad};
  std::lock_guard lock(mutex_);
  State& s = *state_;
  s.vehicle = point;
  if (!s.track.empty()) {
    const TrackPoint& last = s.track.back();
    const double moved = std::hypot(point.x_m - last.x_m, point.y_m - last.y_m, point.z_m - last.z_m);
    if (moved < options_.track_spacing_m && std::abs(wrappedAngle(point.heading_rad - last.heading_rad)) < options_.track_turn_rad) {
      ++s.changes;
      changed_.notify_all();
      return;
    }
  }
  s.track.push_back(point);
  if (s.track.size() > options_.track_max_points) {
    std::vector<TrackPoint> thinned;
    thinned.reserve(s.track.size() / 2 + 1);
    for (std::size_t i = 0; i < s.track.size(); i += 2) thinned.push_back(s.track[i]);
    if (thinned.back().time_s != s.track.back().time_s) thinned.push_back(s.track.back());
    s.track = std::move(thinned);
    ++s.track_epoch;
  }
  ++s.changes;
  changed_.notify_all();
}

void LiveView::setSettings(const AppliedSettings& settings) {
  std::lock_guard lock(mutex_);
  state_->settings = LiveSettings{settings.head, settings.fields};
  ++state_->settings_version;
  ++state_->changes;
  changed_.notify_all();
}

void LiveView::setRecordingPath(std::string path) {
  std::lock_guard lock(mutex_);
  state_->recording_path = std::move(path);
  ++state_->changes;
  changed_.notify_all();
}

void LiveView::addWarning(std::string text) {
  std::lock_guard lock(mutex_);
  state_->warn(std::move(text), options_.max_warnings);
  changed_.notify_all();
}

void LiveView::setMapSource(MapSource source) {
  const bool has_source = static_cast<bool>(source);
  {
    std::lock_guard source_lock(source_mutex_);  // waits for a call in progress
    source_ = std::move(source);
  }
  std::lock_guard lock(mutex_);
  state_->has_source = has_source;
  state_->map_dirty = true;
  state_->redraw_all = true;
  startRasterThread();
  raster_wake_.notify_all();
}

void LiveView::offerMap(OcTree16 map, std::uint64_t beams_shown) {
  std::lock_guard lock(mutex_);
  state_->offered.emplace(std::move(map));
  state_->offered_beams = std::min(beams_shown, state_->beams);
  state_->map_dirty = true;
  state_->redraw_all = true;
  startRasterThread();
  raster_wake_.notify_all();
}

void LiveView::mapReset() {
  std::lock_guard lock(mutex_);
  State& s = *state_;
  ++s.reset_epoch;
  s.offered.reset();
  s.map_drawn_beams = std::max(s.map_drawn_beams, s.beams);  // the beams before are in no map now
  for (auto& [id, page] : s.pages) page.map_drawn_beams = std::max(page.map_drawn_beams, s.beams);
  live::TilePicture empty;  // no tile: the page drops every tile it has
  empty.grid.resolution_m = s.raster.cell_m > 0.0 ? s.raster.cell_m : 0.1;
  empty.grid.tile_px = options_.tile_px;
  empty.z_m = s.sonar ? s.sonar->z_m : 0.0;
  s.publish(empty, s.raster.version + 1, s.beams, now_s(), 0.0);
  s.forget_tiles = true;
  s.redraw_all = true;
  s.changed.clear();
  s.map_dirty = true;
  raster_wake_.notify_all();
  changed_.notify_all();
}

void LiveView::startRasterThread() {
  if (!raster_thread_.joinable()) raster_thread_ = std::jthread([this](std::stop_token stop) { rasterLoop(stop); });
}

void LiveView::rasterLoop(std::stop_token stop) {
  std::unique_lock lock(mutex_);
  State& s = *state_;
  while (!stop.stop_requested()) {
    if (!raster_wake_.wait(lock, stop, [&] { return s.map_dirty && (s.has_source || s.offered); })) return;
    // At most one picture every raster_interval_s: the changes meanwhile go into the next one.
    if (std::isfinite(s.last_raster_start_s)) {
      const auto due = epoch_ + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(s.last_raster_start_s + std::max(options_.raster_interval_s, 2.0 * s.last_render_s)));
      raster_wake_.wait_until(lock, stop, due, [] { return false; });
      if (stop.stop_requested()) return;
    }
    if (!s.map_dirty || !s.sonar) {
      if (!s.sonar) s.map_dirty = false;  // no beam yet: nowhere to centre the window
      continue;
    }
    s.map_dirty = false;
    const std::uint64_t epoch = s.reset_epoch;
    std::optional<OcTree16> offered = std::move(s.offered);
    s.offered.reset();
    const std::uint64_t beams = offered ? s.offered_beams : s.shown;
    const double start_s = now_s();
    live::TileRequest request;
    request.centre_m = {s.sonar->x_m, s.sonar->y_m};
    request.z_m = s.sonar->z_m;
    request.half_width_m = options_.raster_half_width_m > 0.0 ? options_.raster_half_width_m : std::max(10.0, 1.25 * s.range_m);
    request.max_side_px = options_.raster_max_side_px;
    request.full = s.redraw_all || offered || start_s - s.last_full_s >= options_.full_redraw_interval_s;
    request.changed = std::move(s.changed);
    const bool forget = s.forget_tiles;
    const std::uint64_t version = s.raster.version + 1;
    s.redraw_all = false;
    s.forget_tiles = false;
    s.changed.clear();
    if (request.full) s.last_full_s = start_s;
    s.last_raster_start_s = start_s;
    lock.unlock();
    std::optional<live::TilePicture> made;
    std::string error;
    try {
      if (forget) s.map_tiles.clear();
      live::MapTiles::Source source;
      if (offered) {
        source = [&offered](const Eigen::AlignedBox3d&, const ShownMapVisitor& visit) { visit(*offered, {}); };
      } else {
        source = [this](const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) {
          std::lock_guard source_lock(source_mutex_);
          if (!source_) throw NoMapSource{};
          source_(box_m, visit);
        };
      }
      made = s.map_tiles.draw(request, source, version);
    } catch (const NoMapSource&) {
    } catch (const std::exception& caught) {
      error = caught.what();
    }
    const double done_s = now_s();
    lock.lock();
    s.last_render_s = done_s - start_s;
    if (!made) s.redraw_all = true;  // the tiles may be part drawn
    if (!error.empty()) {
      s.warn("map picture: " + error, options_.max_warnings);
      changed_.notify_all();
      continue;
    }
    if (!made) continue;  // no source any more
    if (epoch != s.reset_epoch) {  // a picture of the map before a reset
      s.forget_tiles = true;
      continue;
    }
    s.publish(*made, version, beams, done_s, done_s - start_s);
    pushBounded(s.render_times, done_s - start_s, options_.latency_samples);
    pushBounded(s.copy_times, made->copy_s, options_.latency_samples);
    changed_.notify_all();
  }
}

ViewUpdate LiveView::updateSince(const ViewCursor& cursor) const {
  ViewUpdate update;
  {
    std::lock_guard lock(mutex_);
    const State& s = *state_;
    update.full = !cursor.started || cursor.view_id != id_ || cursor.reset_epoch != s.reset_epoch;
    const std::uint64_t from = update.full ? 0 : cursor.next_beam;
    const std::uint64_t newest_kept = s.beams > options_.fan_beams ? s.beams - options_.fan_beams : 0;
    for (const auto& beam : s.fan) {
      if (beam->seq >= std::max(from, newest_kept)) update.beams.push_back(beam);
    }
    update.track_full = update.full || cursor.track_epoch != s.track_epoch || cursor.track_sent > s.track.size();
    const std::size_t track_from = update.track_full ? 0 : cursor.track_sent;
    update.track.assign(s.track.begin() + static_cast<std::ptrdiff_t>(track_from), s.track.end());
    update.vehicle = s.vehicle;
    if (update.full || cursor.settings_version != s.settings_version) update.settings = s.settings;
    if (s.raster.version != 0 && (update.full || cursor.raster_version != s.raster.version)) {
      update.raster = s.raster;
      // A cursor of a newer picture (a reader of another view) gets every tile.
      const bool all = update.full || cursor.raster_version > s.raster.version;
      for (const auto& tile : s.tiles) {
        if (all || tile->version > cursor.raster_version) update.tiles.push_back(tile);
      }
      std::sort(update.tiles.begin(), update.tiles.end(), [](const auto& a, const auto& b) { return a->version < b->version; });
    }
    update.fan_beams = options_.fan_beams;
    update.cursor = {true, s.beams, s.track_epoch, s.track.size(), s.settings_version, s.raster.version, s.reset_epoch, s.changes, id_};
  }
  update.status = status();
  return update;
}

std::uint64_t LiveView::changes() const {
  std::lock_guard lock(mutex_);
  return state_->changes;
}

std::uint64_t LiveView::waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout, std::stop_token stop) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, stop, timeout, [&] { return state_->changes > seen; });
  return state_->changes;
}

std::pair<RasterInfo, std::shared_ptr<const std::vector<unsigned char>>> LiveView::rasterPng() const {
  RasterInfo info;
  std::vector<std::shared_ptr<const MapTile>> tiles;
  Eigen::Vector2d centre(0.0, 0.0);  // of an empty picture: the sonar
  {
    std::lock_guard lock(mutex_);
    const State& s = *state_;
    if (s.raster.version == 0) return {s.raster, nullptr};
    if (s.composed_version == s.raster.version) return {s.composed_info, s.composed_png};
    info = s.raster;
    tiles = s.tiles;
    if (s.sonar) centre = {s.sonar->x_m, s.sonar->y_m};
  }
  TileGrid grid;
  grid.resolution_m = info.cell_m;  // a pixel per cell: the composition needs cell and tile size only
  grid.tile_px = info.tile_px;
  const MapRaster composed = live::composeTiles(grid, info.z_m, tiles, centre);
  info.north_m = composed.north_m;
  info.west_m = composed.west_m;
  info.cols = composed.image.cols;
  info.rows = composed.image.rows;
  auto png = std::make_shared<const std::vector<unsigned char>>(encodePng(composed.image));
  std::lock_guard lock(mutex_);
  State& s = *state_;
  if (s.raster.version == info.version) {
    s.composed_version = info.version;
    s.composed_info = info;
    s.composed_png = png;
  }
  return {info, png};
}

LiveStatus LiveView::status() const {
  const double now = now_s();
  std::lock_guard lock(mutex_);
  const State& s = *state_;
  LiveStatus status;
  status.clock_s = now;
  status.beams_received = s.beams;
  if (s.first_arrival_s) {
    std::size_t recent = 0;
    for (auto it = s.arrivals.rbegin(); it != s.arrivals.rend() && it->arrival_s > now - kRateWindow_s; ++it) ++recent;
    status.beams_per_s = static_cast<double>(recent) / std::clamp(now - *s.first_arrival_s, 0.5, kRateWindow_s);
  }
  std::vector<double> lags;
  for (const auto& [when_s, lag_s] : s.shown_lags) {
    if (when_s >= now - kRateWindow_s) lags.push_back(lag_s);
  }
  if (!lags.empty()) {
    std::nth_element(lags.begin(), lags.begin() + static_cast<std::ptrdiff_t>(lags.size() / 2), lags.end());
    status.lag_s = lags[lags.size() / 2];
  } else {
    status.lag_s = s.last_lag_s;
  }
  if (const std::optional<double> waiting_since = s.arrivalOf(s.shown); waiting_since && s.shown < s.beams) {
    status.lag_s = std::max(status.lag_s.value_or(0.0), now - *waiting_since);
  }
  status.beams_waiting = s.beams - s.shown;
  status.sweeps = s.sweeps;
  status.recording_path = s.recording_path;
  status.warnings.assign(s.warnings.begin(), s.warnings.end());
  return status;
}

void LiveView::acknowledge(std::span<const std::uint64_t> beam_seqs, std::span<const std::uint64_t> raster_versions,
                           double held_s, const std::string& page) {
  constexpr std::size_t kPagesKept = 16;
  const double drawn_s = now_s() - std::max(held_s, 0.0);
  std::lock_guard lock(mutex_);
  State& s = *state_;
  const std::uint64_t first = s.beams - s.arrivals.size();
  State::PageLatencies* own = nullptr;
  if (!page.empty()) {
    if (!s.pages.contains(page) && s.pages.size() >= kPagesKept) {
      s.pages.erase(std::min_element(s.pages.begin(), s.pages.end(), [](const auto& a, const auto& b) {
        return a.second.heard_s < b.second.heard_s;
      }));
    }
    own = &s.pages[page];
    own->heard_s = drawn_s;
  }
  for (const std::uint64_t seq : beam_seqs) {
    if (seq < std::max(first, s.timed_from) || seq >= s.beams) continue;
    State::Arrival& arrival = s.arrivals[seq - first];
    if (own && seq >= own->fan_drawn_from) {
      pushBounded(own->fan, drawn_s - arrival.arrival_s, options_.latency_samples);
      own->fan_drawn_from = seq + 1;
    }
    if (arrival.fan_drawn) continue;
    arrival.fan_drawn = true;
    pushBounded(s.fan_latencies, drawn_s - arrival.arrival_s, options_.latency_samples);
  }
  for (const std::uint64_t version : raster_versions) {
    const auto it = std::find_if(s.raster_beams.begin(), s.raster_beams.end(),
                                 [&](const auto& entry) { return entry.first == version; });
    if (it == s.raster_beams.end()) continue;
    const auto count = [&](std::deque<double>& latencies, std::uint64_t& drawn_beams) {
      if (it->second <= drawn_beams) return;
      for (std::uint64_t seq = std::max({drawn_beams, first, s.timed_from}); seq < it->second; ++seq) {
        pushBounded(latencies, drawn_s - s.arrivals[seq - first].arrival_s, options_.latency_samples);
      }
      drawn_beams = it->second;
    };
    if (own) count(own->map, own->map_drawn_beams);
    count(s.map_latencies, s.map_drawn_beams);
  }
}

LiveLatencies LiveView::latencies(const std::string& page) const {
  std::lock_guard lock(mutex_);
  const State& s = *state_;
  LiveLatencies latencies{statsOf(s.fan_latencies), statsOf(s.map_latencies), statsOf(s.render_times),
                          statsOf(s.copy_times), s.raster.png_bytes};
  if (!page.empty()) {
    const auto it = s.pages.find(page);
    latencies.fan = it == s.pages.end() ? LatencyStats{} : statsOf(it->second.fan);
    latencies.map = it == s.pages.end() ? LatencyStats{} : statsOf(it->second.map);
  }
  return latencies;
}

void LiveView::resetLatencies() {
  std::lock_guard lock(mutex_);
  State& s = *state_;
  s.fan_latencies.clear();
  s.map_latencies.clear();
  s.render_times.clear();
  s.copy_times.clear();
  s.timed_from = s.beams;
  s.map_drawn_beams = std::max(s.map_drawn_beams, s.beams);
  s.pages.clear();
}

}  // namespace sonarmap
