// The live page's view state (live/live_view.hpp): beams pooled and kept for the fan, updates
// since a cursor, the track thinned, the map picture made on the view's own thread (throttled,
// never blocking the session, dropped across a reset), and the latencies from acknowledgements.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <numbers>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/live/live_view.hpp"
#include "sonarmap/live/map_raster.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

Beam beamOf(std::size_t bins, double bearing_rad, std::uint8_t level = 10) {
  Beam beam;
  beam.bearing_rad = bearing_rad;
  beam.bin_length_m = 50.0 / static_cast<double>(bins);
  beam.intensities.assign(bins, level);
  return beam;
}

/// A map with a wall 5 m north of the origin in the layer z ∈ [0, 0.1).
OcTree16 wallMap() {
  OcTree16 map(0.1);
  for (double y = -3.0; y < 3.0; y += 0.1) {
    for (int i = 0; i < 3; ++i) map.integrate(map.coder().keyOfChecked({5.05, y + 0.05, 0.05}), true);
  }
  for (double x = 0.0; x < 5.0; x += 0.1) map.integrate(map.coder().keyOfChecked({x + 0.05, 0.05, 0.05}), false);
  map.updateInnerOccupancy();
  return map;
}

/// Waits up to `limit` for `done`.
template <class Done>
bool eventually(Done done, std::chrono::milliseconds limit = 5000ms) {
  const auto until = Clock::now() + limit;
  while (Clock::now() < until) {
    if (done()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return done();
}

TEST(LiveView, PlacesTheSonar) {
  const SonarPlacement still = placementOf(staticSonarToMap());
  EXPECT_NEAR(still.yaw_rad, 0.0, 1e-12);  // bearing 0 north
  EXPECT_TRUE(still.clockwise);
  NavSample fix;
  fix.position_ned_m = {3.0, 4.0, 2.0};
  fix.yaw_rad = std::numbers::pi / 2;  // heading east: bearing 0 points map −y
  const SonarPlacement moved = placementOf(sonarToMap(fix, defaultSonarToBody()));
  EXPECT_NEAR(moved.x_m, 3.0, 1e-12);
  EXPECT_NEAR(moved.y_m, -4.0, 1e-12);
  EXPECT_NEAR(moved.z_m, -2.0, 1e-12);
  EXPECT_NEAR(moved.yaw_rad, -std::numbers::pi / 2, 1e-12);
  Eigen::Isometry3d upside_down = Eigen::Isometry3d::Identity();
  upside_down.linear() = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_FALSE(placementOf(sonarToMap(NavSample{}, upside_down)).clockwise);
}

TEST(LiveView, PoolsBinsAndKeepsTheFan) {
  LiveViewOptions options;
  options.fan_beams = 10;
  LiveView view(Clock::now(), options);
  Beam beam = beamOf(1200, 0.5);
  beam.intensities[5] = 200;   // pooled with bins 3…5
  beam.intensities[1199] = 77;  // the last pooled bin
  EXPECT_EQ(view.addBeam(beam, 1.0, {}), 0U);
  ViewUpdate first = view.updateSince({});
  ASSERT_TRUE(first.full);
  ASSERT_EQ(first.beams.size(), 1U);
  const LiveBeam& pooled = *first.beams[0];
  EXPECT_EQ(pooled.intensities.size(), 400U);  // 1200 bins in threes: ≤ 512
  EXPECT_NEAR(pooled.bin_length_m, 3 * 50.0 / 1200, 1e-12);
  EXPECT_EQ(pooled.intensities[1], 200);
  EXPECT_EQ(pooled.intensities[0], 10);
  EXPECT_EQ(pooled.intensities[399], 77);
  EXPECT_DOUBLE_EQ(pooled.arrival_s, 1.0);

  for (int i = 1; i < 25; ++i) view.addBeam(beamOf(300, 0.01 * i), 1.0 + i, {});
  const ViewUpdate next = view.updateSince(first.cursor);
  EXPECT_FALSE(next.full);
  ASSERT_EQ(next.beams.size(), 10U);  // the fan keeps the newest 10
  EXPECT_EQ(next.beams.front()->seq, 15U);
  EXPECT_EQ(next.beams.back()->seq, 24U);
  EXPECT_EQ(next.beams.back()->intensities.size(), 300U);
  const ViewUpdate none = view.updateSince(next.cursor);
  EXPECT_FALSE(none.full);
  EXPECT_TRUE(none.beams.empty());
  LiveView restarted(Clock::now(), options);
  EXPECT_TRUE(restarted.updateSince(next.cursor).full);  // a cursor of another view starts over
  EXPECT_FALSE(none.settings);
  EXPECT_EQ(none.status.beams_received, 25U);
}

TEST(LiveView, SendsSettingsTrackAndStatusWhenTheyChange) {
  LiveViewOptions options;
  options.track_max_points = 8;
  LiveView view(Clock::now(), options);
  view.setSettings(AppliedSettings{"Ping360", {{"range_m", "50"}, {"gain", "normal"}}});
  ViewUpdate update = view.updateSince({});
  ASSERT_TRUE(update.settings);
  EXPECT_EQ(update.settings->device, "Ping360");
  EXPECT_EQ(update.settings->fields.at(0).second, "50");
  update = view.updateSince(update.cursor);
  EXPECT_FALSE(update.settings);

  NavSample fix;
  for (int i = 0; i < 5; ++i) {  // 0.1 m apart: one point kept of the first three, then 0.3 m on
    fix.time_s = i;
    fix.position_ned_m = {0.1 * i, 0.0, 2.0};
    view.addNavFix(fix);
  }
  update = view.updateSince(update.cursor);
  EXPECT_FALSE(update.track_full);
  ASSERT_EQ(update.track.size(), 2U);
  EXPECT_DOUBLE_EQ(update.track[1].x_m, 0.3);
  EXPECT_DOUBLE_EQ(update.track[1].z_m, -2.0);  // map z up
  ASSERT_TRUE(update.vehicle);
  EXPECT_DOUBLE_EQ(update.vehicle->x_m, 0.4);  // the latest fix, kept or not
  for (int i = 5; i < 40; ++i) {
    fix.time_s = i;
    fix.position_ned_m = {1.0 * i, 0.0, 2.0};
    view.addNavFix(fix);
  }
  const ViewUpdate thinned = view.updateSince(update.cursor);
  EXPECT_TRUE(thinned.track_full);  // thinned: sent whole
  EXPECT_LE(thinned.track.size(), 8U);
  EXPECT_DOUBLE_EQ(thinned.track.back().x_m, 39.0);

  view.addWarning("navigation late");
  view.addWarning("navigation late");
  view.setRecordingPath("/data/run.bin");
  const LiveStatus status = view.status();
  ASSERT_EQ(status.warnings.size(), 1U);
  EXPECT_EQ(status.warnings[0], "navigation late (x2)");
  EXPECT_EQ(status.recording_path, "/data/run.bin");
}

TEST(LiveView, TimesTheLagToTheMapAsShown) {
  LiveView view(Clock::now());
  EXPECT_FALSE(view.status().lag_s);
  for (int i = 0; i < 10; ++i) view.addBeam(beamOf(100, 0.0), view.now_s() - 0.5, {});  // arrived 0.5 s ago
  view.mapShows(4);
  LiveStatus status = view.status();
  EXPECT_EQ(status.beams_waiting, 6U);
  ASSERT_TRUE(status.lag_s);
  EXPECT_GE(*status.lag_s, 0.5);  // the oldest waiting beam's wait
  EXPECT_LT(*status.lag_s, 5.0);
  EXPECT_GT(status.beams_per_s, 4.0);  // 10 beams within the last 2 s (at least 0.5 s of run)
  view.mapShows(10);
  status = view.status();
  EXPECT_EQ(status.beams_waiting, 0U);
  EXPECT_NEAR(*status.lag_s, 0.5, 0.4);
}

TEST(LiveView, MakesTheMapPictureOnItsOwnThreadThrottled) {
  LiveViewOptions options;
  options.raster_interval_s = 0.1;
  options.raster_half_width_m = 20.0;  // 7 × 7 tiles of 6.4 m
  options.tile_px = 64;
  LiveView view(Clock::now(), options);
  std::atomic<int> copies{0};
  const OcTree16 map = wallMap();
  view.setMapSource([&](const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) {
    if (!box_m.isEmpty()) {  // not only the resolution asked for
      ++copies;
      std::this_thread::sleep_for(2ms);  // a slow read (about 0.1 s a picture): the session must not wait for it
    }
    visit(map, {});
  });
  EXPECT_EQ(view.rasterPng().second, nullptr);
  const auto start = Clock::now();
  double slowest_s = 0.0;
  for (int i = 0; i < 50; ++i) {  // 50 beams in 0.5 s
    const auto call = Clock::now();
    view.addBeam(beamOf(400, 0.01 * i), view.now_s(), placementOf(staticSonarToMap()));
    view.mapShows(i + 1);
    slowest_s = std::max(slowest_s, std::chrono::duration<double>(Clock::now() - call).count());
    std::this_thread::sleep_until(start + (i + 1) * 10ms);
  }
  EXPECT_LT(slowest_s, 0.02);  // never the 50 ms of a copy
  ASSERT_TRUE(eventually([&] { return view.rasterPng().first.beams == 50; }));
  // At most one picture per 0.1 s, each started after a change: about 0.5 s / (0.1 + 0.1) s.
  EXPECT_LE(view.rasterPng().first.version, 8U);
  EXPECT_GE(view.rasterPng().first.version, 2U);
  const auto [info, png] = view.rasterPng();
  ASSERT_NE(png, nullptr);
  const cv::Mat decoded = cv::imdecode(*png, cv::IMREAD_GRAYSCALE);
  RasterWindow window;
  window.half_width_m = 20.0;
  const MapRaster expected = rasterizeMap(map, window);
  ASSERT_EQ(decoded.size(), expected.image.size());
  EXPECT_EQ(cv::countNonZero(decoded != expected.image), 0);
  EXPECT_EQ(info.cols, expected.image.cols);
  EXPECT_DOUBLE_EQ(info.north_m, expected.north_m);
  EXPECT_EQ(info.occupied_px, 60U);
  for (const auto& tile : view.updateSince({}).tiles) EXPECT_GT(tile->png_bytes, 0U);
  EXPECT_EQ(info.tile_px, 64);
  EXPECT_GE(info.copy_s, 0.05);  // the source's 50 ms, timed apart
  EXPECT_GE(info.render_s, info.copy_s);
  EXPECT_GE(view.latencies().copy.median_s, 0.05);
  EXPECT_GE(copies.load(), 49);  // each tile drawn from its own part of the map, all 49 in the first picture
  const int settled = copies.load();
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(copies.load(), settled);  // no change, no picture
  view.setMapSource({});
}

TEST(LiveView, AResetDropsThePictureInTheMaking) {
  LiveViewOptions options;
  options.raster_interval_s = 0.0;
  LiveView view(Clock::now(), options);
  std::atomic<bool> release{false}, copying{false};
  std::atomic<int> copies{0};
  const OcTree16 map = wallMap();
  view.setMapSource([&](const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) {
    copying = true;
    while (!release) std::this_thread::sleep_for(1ms);
    if (!box_m.isEmpty()) ++copies;
    visit(map, {});
  });
  view.addBeam(beamOf(100, 0.0), view.now_s(), {});
  view.mapShows(1);
  const ViewCursor before = view.updateSince({}).cursor;
  ASSERT_TRUE(eventually([&] { return copying.load(); }));
  view.mapReset();  // while the old map is being copied
  const RasterInfo after_reset = view.rasterPng().first;
  EXPECT_EQ(after_reset.occupied_px + after_reset.free_px, 0U);  // empty at once
  release = true;
  ASSERT_TRUE(eventually([&] { return copies.load() >= 2; }));  // the stale one dropped, a new one made
  ASSERT_TRUE(eventually([&] { return view.rasterPng().first.version > after_reset.version; }));
  EXPECT_EQ(view.rasterPng().first.version, after_reset.version + 1);  // not two: the stale one was not published
  EXPECT_TRUE(view.updateSince(before).full);  // a reset starts the readers over
  view.setMapSource({});
}

TEST(LiveView, RedrawsOnlyTheTilesItsBeamsReached) {
  LiveViewOptions options;
  options.raster_interval_s = 0.0;
  options.full_redraw_interval_s = 3600.0;  // only what the beams reached
  options.raster_half_width_m = 60.0;       // 0.1 m voxels, 6.4 m tiles of 64 px: tiles −10 … 9 each way
  options.tile_px = 64;
  LiveView view(Clock::now(), options);
  std::mutex map_mutex;
  OcTree16 map = wallMap();
  std::atomic<int> copies{0};
  view.setMapSource([&](const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) {
    const std::lock_guard lock(map_mutex);
    if (!box_m.isEmpty()) ++copies;
    visit(map, {});
  });
  const auto shows = [&](std::uint64_t version) {
    return eventually([&] { return view.rasterPng().first.version >= version; });
  };
  const auto mark = [&](double x, double y, bool occupied) {
    const std::lock_guard lock(map_mutex);
    for (int i = 0; i < 3; ++i) map.integrate(map.coder().keyOfChecked({x, y, 0.05}), occupied);
    map.updateInnerOccupancy();
  };
  view.addBeam(beamOf(100, 0.0), view.now_s(), placementOf(staticSonarToMap()));  // 50 m north
  view.mapShows(1);
  ASSERT_TRUE(shows(1));
  const RasterInfo first = view.rasterPng().first;
  EXPECT_EQ(first.tiles.size(), 400U);
  EXPECT_EQ(first.tiles_drawn, 400U);
  EXPECT_EQ(first.occupied_px, 60U);

  // A beam east (bearing π/2 clockwise: map −y) and a wall it reached, and one it did not reach (west).
  mark(0.05, -20.05, true);
  mark(0.05, 20.05, true);
  view.addBeam(beamOf(100, std::numbers::pi / 2), view.now_s(), placementOf(staticSonarToMap()));
  view.mapShows(2);
  ASSERT_TRUE(shows(2));
  const RasterInfo second = view.rasterPng().first;
  EXPECT_LE(second.tiles_drawn, 50U);  // the tiles within 6 m of the beam (50 m · sin 0.1 + 1 m), not 400
  EXPECT_GE(second.tiles_drawn, 9U);
  EXPECT_EQ(second.tiles_changed, 1U);  // the tile holding (0, −20)
  EXPECT_EQ(second.occupied_px, 61U);   // the west voxel is not redrawn until a full redraw
  const ViewUpdate update = view.updateSince(view.updateSince({}).cursor);
  EXPECT_FALSE(update.raster);  // nothing newer

  // A committed sweep draws every tile again: the west voxel shows, the tiles that did not change keep their version.
  view.setSweeps(1);
  ASSERT_TRUE(shows(3));
  const auto [third, png] = view.rasterPng();
  EXPECT_EQ(third.tiles_drawn, 400U);
  EXPECT_EQ(third.tiles_changed, 1U);
  EXPECT_EQ(third.occupied_px, 62U);
  RasterWindow window;
  window.half_width_m = 60.0;
  const MapRaster expected = rasterizeMap(map, window);
  const cv::Mat decoded = cv::imdecode(*png, cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(decoded.size(), expected.image.size());
  EXPECT_EQ(cv::countNonZero(decoded != expected.image), 0);
  EXPECT_DOUBLE_EQ(third.north_m, expected.north_m);
  EXPECT_DOUBLE_EQ(third.west_m, expected.west_m);
  // A reader that saw the second picture gets the one tile that changed since.
  ViewCursor at_second;
  at_second.started = true;
  at_second.raster_version = second.version;
  at_second.view_id = view.updateSince({}).cursor.view_id;
  at_second.next_beam = 2;
  const ViewUpdate since_second = view.updateSince(at_second);
  ASSERT_TRUE(since_second.raster);
  ASSERT_EQ(since_second.tiles.size(), 1U);
  EXPECT_EQ(since_second.tiles[0]->version, third.version);
  EXPECT_EQ(view.updateSince({}).tiles.size(), 400U);  // a new reader gets every tile
  view.setMapSource({});
}

TEST(LiveView, TakesAMapHandedOver) {
  LiveView view(Clock::now());
  view.addBeam(beamOf(100, 0.0), view.now_s(), {});
  view.offerMap(wallMap(), 1);
  ASSERT_TRUE(eventually([&] { return view.rasterPng().first.version == 1; }));
  EXPECT_EQ(view.rasterPng().first.occupied_px, 60U);
  EXPECT_EQ(view.rasterPng().first.beams, 1U);
}

TEST(LiveView, MeasuresArrivalToPixelsFromAcknowledgements) {
  LiveView view(Clock::now());
  for (int i = 0; i < 4; ++i) view.addBeam(beamOf(100, 0.0), view.now_s() - 0.2, {});
  const std::uint64_t fans[] = {0, 1, 1, 2, 99};  // 1 twice (two pages), 99 unknown
  view.acknowledge(fans, {}, 0.05);
  LiveLatencies latencies = view.latencies();
  EXPECT_EQ(latencies.fan.count, 3U);
  EXPECT_NEAR(latencies.fan.median_s, 0.15, 0.05);  // 0.2 s ago, drawn 0.05 s before the ack
  EXPECT_EQ(latencies.map.count, 0U);

  view.offerMap(wallMap(), 3);
  ASSERT_TRUE(eventually([&] { return view.rasterPng().first.version == 1; }));
  const std::uint64_t rasters[] = {1};
  view.acknowledge({}, rasters);
  view.acknowledge({}, rasters);  // a second page: counted once
  latencies = view.latencies();
  EXPECT_EQ(latencies.map.count, 3U);  // beams 0, 1, 2 were in that picture
  EXPECT_GE(latencies.map.median_s, 0.2);
  EXPECT_EQ(latencies.render.count, 1U);
  EXPECT_GT(latencies.last_png_bytes, 0U);

  view.resetLatencies();
  const std::uint64_t late[] = {3};
  view.acknowledge(late, {});  // arrived before the reset: not timed
  EXPECT_EQ(view.latencies().fan.count, 0U);
}

TEST(LiveView, WaitsForChangesAndStops) {
  LiveView view(Clock::now());
  const std::uint64_t seen = view.changes();
  std::stop_source stop;
  std::thread writer([&] {
    std::this_thread::sleep_for(30ms);
    view.addBeam(beamOf(10, 0.0), view.now_s(), {});
  });
  EXPECT_GT(view.waitForChange(seen, 5000ms, stop.get_token()), seen);
  writer.join();
  const auto start = Clock::now();
  std::thread stopper([&] {
    std::this_thread::sleep_for(30ms);
    stop.request_stop();
  });
  view.waitForChange(view.changes(), 5000ms, stop.get_token());
  EXPECT_LT(Clock::now() - start, 1000ms);
  stopper.join();
  EXPECT_THROW(LiveView(Clock::now(), LiveViewOptions{.max_bins = 4}), ValueError);
}

}  // namespace
}  // namespace sonarmap
