// A live session without a sonar, for the page's browser test (page_test.js) and for measuring:
// a simulated head (MsisBeamSimulator, a preset's settings, a built-in scene at the head's range)
// feeds a real OnlineMapper (provisional beams) and a LiveView, served by a WebServer.
//
//   sonarmap_live_fake_session --out DIR [--port 0] [--rate 12] [--preset ping360] [--scene harbour]
//                              [--resolution 0.1] [--seed 1]
//
// Commands on standard input, one a line; each answers one line on standard output:
//   feed N   N beams at --rate beams a second (the head's pace), then
//            "fed first=SEQ last=SEQ shown=N sweeps=N bearing_from=RAD bearing_to=RAD"
//   fast N   the same as fast as it can
//   status   "status beams=N shown=N sweeps=N"
//   cost     what a map picture costs now, the best of three: "cost leaves=N copy_ms=T raster_ms=T
//            png_ms=T png_bytes=N cols=N rows=N" (copy: OnlineMapper::shownSnapshot)
//   quit     "bye", and the program ends (the server stops first)
// It prints "listening URL" once it serves. "Save map" writes DIR/map.bt (the map as shown),
// DIR/recording.txt and DIR/map_cells.json: the occupied cells of the .bt as read back, at the
// sonar's height (cellsInSlice), for comparing with what the page drew.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

#include "sonarmap/io/map_file.hpp"
#include "sonarmap/live/live_view.hpp"
#include "sonarmap/live/map_raster.hpp"
#include "sonarmap/live/web_server.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/sim/beam_simulator.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"
#include "sonarmap/sonar/png_writer.hpp"

namespace {

using namespace sonarmap;
using Clock = std::chrono::steady_clock;

struct Args {
  std::filesystem::path out;
  int port = 0;
  double rate = 12.0;
  std::string preset = "ping360";
  std::string scene = "harbour";
  double resolution_m = 0.1;
  std::uint64_t seed = 1;
};

Args parse(int argc, char** argv) {
  Args args;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string name = argv[i], value = argv[i + 1];
    if (name == "--out") args.out = value;
    else if (name == "--port") args.port = std::stoi(value);
    else if (name == "--rate") args.rate = std::stod(value);
    else if (name == "--preset") args.preset = value;
    else if (name == "--scene") args.scene = value;
    else if (name == "--resolution") args.resolution_m = std::stod(value);
    else if (name == "--seed") args.seed = std::stoull(value);
    else throw std::runtime_error("unknown option " + name);
  }
  if (args.out.empty()) throw std::runtime_error("--out DIR is required");
  return args;
}

/// The mapper, swapped for a new one by "Reset map"; beams before a reset count as shown.
class Session {
 public:
  Session(const Args& args, const SonarPreset& preset, LiveView& view)
      : args_(args), view_(view), preset_(preset),
        simulator_(builtinScene(args.scene, preset.head.range_m, preset.head.vertical_beam_width_rad), preset.head,
                   preset.echo, staticTrajectory(), defaultSonarToBody(), args.seed) {
    options_.resolution_m = args.resolution_m;
    options_.beam_width_rad = preset.head.horizontal_beam_width_rad;
    mapper_ = newMapper();
  }

  std::shared_ptr<OnlineMapper> mapper() const {
    std::lock_guard lock(pointer_mutex_);
    return mapper_;
  }

  /// `count` beams, paced at --rate when `paced`.
  std::string feed(std::size_t count, bool paced) {
    const Clock::time_point start = Clock::now();
    std::uint64_t first = 0, last = 0;
    double bearing_from = 0.0, bearing_to = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      if (paced) std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(i / args_.rate)));
      const double bearing = std::fmod(static_cast<double>(next_) * preset_.head.step_rad, 2.0 * std::numbers::pi);
      Beam beam = simulator_.simulate(static_cast<double>(next_) * preset_.head.beam_period_s, bearing);
      const std::uint64_t seq = view_.addBeam(beam, view_.now_s(), placementOf(staticSonarToMap()));
      std::lock_guard lock(feed_mutex_);
      const std::shared_ptr<OnlineMapper> mapper = this->mapper();
      mapper->addBeam(std::move(beam));
      ++given_;
      view_.mapShows(before_mapper_ + given_ - mapper->beamsUnshown());
      view_.setSweeps(mapper->sweepsIntegrated());  // as LiveSession: the sweeps of the map since its reset
      if (i == 0) {
        first = seq;
        bearing_from = bearing;
      }
      last = seq;
      bearing_to = bearing;
      ++next_;
    }
    std::ostringstream line;
    line << "fed first=" << first << " last=" << last << " shown=" << shown() << " sweeps=" << sweeps()
         << " bearing_from=" << bearing_from << " bearing_to=" << bearing_to;
    return line.str();
  }

  std::string status() {
    std::ostringstream line;
    line << "status beams=" << next_ << " shown=" << shown() << " sweeps=" << sweeps();
    return line.str();
  }

  /// The raster thread's work, timed here on the command's thread.
  std::string cost() {
    double copy_ms = 1e9, raster_ms = 1e9, png_ms = 1e9;
    std::size_t bytes = 0, leaves = 0;
    MapRaster raster;
    const auto ms = [](Clock::time_point since) { return std::chrono::duration<double, std::milli>(Clock::now() - since).count(); };
    for (int repeat = 0; repeat < 3; ++repeat) {
      auto start = Clock::now();
      const OcTree16 map = mapper()->shownSnapshot();
      copy_ms = std::min(copy_ms, ms(start));
      leaves = map.counts().leaves;
      start = Clock::now();
      RasterWindow window;
      window.half_width_m = 1.25 * preset_.head.range_m;
      raster = rasterizeMap(map, window);
      raster_ms = std::min(raster_ms, ms(start));
      start = Clock::now();
      bytes = encodePng(raster.image).size();
      png_ms = std::min(png_ms, ms(start));
    }
    std::ostringstream line;
    line << "cost leaves=" << leaves << " copy_ms=" << copy_ms << " raster_ms=" << raster_ms << " png_ms=" << png_ms
         << " png_bytes=" << bytes << " cols=" << raster.image.cols << " rows=" << raster.image.rows;
    return line.str();
  }

  std::vector<std::pair<std::string, std::string>> save() {
    const std::string map_path = (args_.out / "map.bt").string();
    writeMapFile(mapper()->shownSnapshot(), map_path);
    const OcTree16 written = readMapFile(map_path);
    std::ofstream cells(args_.out / "map_cells.json");
    cells << "{\"resolution\":" << written.resolution_m() << ",\"z\":0,\"occupied\":[";
    bool comma = false;
    for (const Eigen::Vector2d& cell : cellsInSlice(written, 0.0, Occupancy::kOccupied)) {
      cells << (comma ? "," : "") << "[" << cell.x() << "," << cell.y() << "]";
      comma = true;
    }
    cells << "]}\n";
    std::ofstream(args_.out / "recording.txt") << next_ << " beams simulated\n";
    return {{"map", map_path}, {"log", (args_.out / "recording.txt").string()},
            {"cells", (args_.out / "map_cells.json").string()}};
  }

  void reset() {
    std::lock_guard lock(feed_mutex_);
    const std::shared_ptr<OnlineMapper> old = mapper();
    before_mapper_ += given_;
    sweeps_before_ += old->sweepsIntegrated();
    given_ = 0;
    std::lock_guard pointer_lock(pointer_mutex_);
    mapper_ = newMapper();
  }

 private:
  std::shared_ptr<OnlineMapper> newMapper() const {
    return std::make_shared<OnlineMapper>(options_, OnlineIntegration::kProvisionalBeams);
  }
  std::uint64_t shown() {
    std::lock_guard lock(feed_mutex_);
    return before_mapper_ + given_ - mapper()->beamsUnshown();
  }
  std::size_t sweeps() {
    std::lock_guard lock(feed_mutex_);
    return sweeps_before_ + mapper()->sweepsIntegrated();
  }

  const Args& args_;
  LiveView& view_;
  SonarPreset preset_;
  MsisBeamSimulator simulator_;
  MapperOptions options_;
  mutable std::mutex pointer_mutex_;
  std::mutex feed_mutex_;  ///< a beam is mapped, or the mapper replaced
  std::shared_ptr<OnlineMapper> mapper_;
  std::uint64_t next_ = 0;           ///< beams simulated
  std::uint64_t before_mapper_ = 0;  ///< beams given to mappers before the current one
  std::uint64_t given_ = 0;          ///< beams given to the current mapper
  std::size_t sweeps_before_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    std::filesystem::create_directories(args.out);
    const SonarPreset preset = sonarPreset(args.preset);
    // Pictures every 0.2 s rather than the default 0.5 s: the page test's bound on the map's lag
    // (p95 under 1 s) then holds on a sanitizer build, whose pictures cost several times as much.
    LiveViewOptions view_options;
    view_options.raster_interval_s = 0.2;
    LiveView view(Clock::now(), view_options);
    Session session(args, preset, view);
    view.setSettings(AppliedSettings{preset.name + " (simulated)",
                                     {{"range_m", std::to_string(static_cast<int>(preset.head.range_m))},
                                      {"samples", std::to_string(preset.head.bins)},
                                      {"step_deg", std::to_string(preset.head.step_rad * 180.0 / std::numbers::pi).substr(0, 4)},
                                      {"scene", args.scene}}});
    view.setRecordingPath((args.out / "recording.txt").string());
    view.setMapSource([&session](const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) {
      session.mapper()->visitShown(box_m, visit);
    });
    // The view's raster thread stops calling into the session before the session goes.
    struct SourceGuard {
      LiveView& view;
      ~SourceGuard() { view.setMapSource({}); }
    } source_guard{view};
    WebServer server(view, WebServerOptions{"127.0.0.1", args.port, "sonarmap live (test)"},
                     WebHandlers{[&session] { return session.save(); }, [&session] { session.reset(); }});
    std::cout << "listening " << server.url() << std::endl;
    for (std::string line; std::getline(std::cin, line);) {
      std::istringstream command(line);
      std::string verb;
      std::size_t count = 0;
      command >> verb >> count;
      if (verb == "feed" || verb == "fast") {
        std::cout << session.feed(count, verb == "feed") << std::endl;
      } else if (verb == "status") {
        std::cout << session.status() << std::endl;
      } else if (verb == "cost") {
        std::cout << session.cost() << std::endl;
      } else if (verb == "quit") {
        break;
      } else if (!verb.empty()) {
        std::cout << "error unknown command " << verb << std::endl;
      }
    }
    const auto stop_start = Clock::now();
    server.stop();
    std::cout << "bye stop_ms=" << std::chrono::duration<double, std::milli>(Clock::now() - stop_start).count()
              << std::endl;
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "fake_session: " << error.what() << std::endl;
    return 1;
  }
}
