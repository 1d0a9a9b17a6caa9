// sonarmap_live_latency: how long a beam takes from its last byte to the map as shown and to the
// committed map, on one core for the mapping: a sonar log encoded as the head sends it (a SeaNet
// capture, wire_encoder.hpp) is replayed beam by beam at the head's own beam rate (the log's
// median beam interval) and at RATE times it by a producer thread; the mapping thread decodes
// each beam's bytes as they arrive and gives the beam to an OnlineMapper with
// OnlineIntegration::kProvisionalBeams (`live`'s default: shown at once on the provisional layer,
// committed when its sweep is final), and stamps the beams shown and committed since the last one.
// Latency = the stamp − the time the beam's last byte was handed over. The beams that arrive
// before the first sweep is committed wait for its calibration and are reported apart; the
// --slam row maps through OnlineSlam without navigation (a scan per sweep, matched, the map
// rebuilt when a loop closes); "late" counts beams still waiting when the next one arrives (a
// backlog; nothing is dropped: the queue holds every beam, so a backlog shows as latency). Beams
// committed only at the end of the replay are not timed. At most 30 s of replay per row (at the
// head's own rate: its first sweeps).
//
// Usage: sonarmap_live_latency LOG [RATE ...]   (default rates: 1 20; LOG e.g. the CRAS .mat)
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "sonarmap/core/statistics.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/seanet_capture.hpp"
#include "sonarmap/formats/wire_encoder.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/slam/online_slam.hpp"

namespace {

using namespace sonarmap;
using Clock = std::chrono::steady_clock;

struct Case {
  const char* name;
  BeamModel model;
  double resolution_m;
  bool slam = false;  ///< live --slam without navigation (OnlineSlam): scans, matches, map rebuilds
};

/// The median interval between consecutive beams of the log, seconds (0.043 s on the CRAS Micron).
double beamInterval_s(const SonarLog& log) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < log.beams.size(); ++i) steps.push_back(log.beams[i].time_s - log.beams[i - 1].time_s);
  if (steps.empty()) return 0.05;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return std::max(1e-4, steps[steps.size() / 2]);
}

/// The fraction `p` percentile of a copy of `values` (they are printed in arrival order later).
double percentileOf(std::vector<double> values, double p) { return percentile(values, p); }

double maxOf(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

/// The latencies of the beams that reach one stage (shown, committed), in arrival order.
struct Stage {
  std::size_t reached = 0;          ///< beams that reached it so far (the oldest)
  std::vector<double> latency_ms;   ///< of those that arrived after the first sweep was committed
  std::vector<double> warmup_ms;    ///< of those that arrived before
  /// The beams up to `reached` reached the stage at `now`.
  void settle(std::size_t now_reached, Clock::time_point now, const std::vector<Clock::time_point>& sent,
              const std::vector<bool>& calibrating) {
    for (; reached < now_reached; ++reached) {
      (calibrating[reached] ? warmup_ms : latency_ms)
          .push_back(std::chrono::duration<double, std::milli>(now - sent[reached]).count());
    }
  }
};

struct Arrival {
  std::vector<std::uint8_t> bytes;  // one beam's packet
  Clock::time_point sent;
};

/// Replays `packets` every `interval_s` seconds into a mapper; prints one table row.
void replay(const std::vector<std::vector<std::uint8_t>>& all_packets, double interval_s, double rate, const Case& c) {
  // At most 30 s of replay: at the head's own rate, the first few sweeps.
  const auto beams = std::min(all_packets.size(), static_cast<std::size_t>(30.0 * rate / interval_s));
  const std::vector<std::vector<std::uint8_t>> packets(all_packets.begin(), all_packets.begin() + static_cast<std::ptrdiff_t>(beams));
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<Arrival> queue;
  bool done = false;
  std::thread producer([&] {
    const Clock::time_point start = Clock::now();
    for (std::size_t i = 0; i < packets.size(); ++i) {
      std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(static_cast<double>(i) * interval_s / rate)));
      const std::lock_guard lock(mutex);
      queue.push_back({packets[i], Clock::now()});
      ready.notify_one();
    }
    const std::lock_guard lock(mutex);
    done = true;
    ready.notify_one();
  });
  MapperOptions options;
  options.beam_model = c.model;
  options.resolution_m = c.resolution_m;
  options.pipeline_detection = false;
  std::optional<OnlineMapper> plain;
  std::optional<OnlineSlam> slam;
  if (c.slam) {
    slam.emplace(options, defaultSonarToBody(), false, SlamOptions{}, OnlineIntegration::kProvisionalBeams);
  } else {
    plain.emplace(options, OnlineIntegration::kProvisionalBeams);
  }
  std::vector<Clock::time_point> sent;
  std::vector<bool> calibrating;  ///< arrived before the first sweep was committed
  Stage shown, committed;
  std::size_t late = 0;
  for (;;) {
    Arrival arrival;
    {
      std::unique_lock lock(mutex);
      ready.wait(lock, [&] { return done || !queue.empty(); });
      if (queue.empty()) break;
      arrival = std::move(queue.front());
      queue.pop_front();
      late += queue.empty() ? 0 : 1;
    }
    const SonarLog decoded = parseSeaNetCapture(std::span(arrival.bytes.data(), arrival.bytes.size()), "wire");
    for (const Beam& beam : decoded.beams) {
      sent.push_back(arrival.sent);
      calibrating.push_back((slam ? slam->sweepsIntegrated() : plain->sweepsIntegrated()) == 0);
      if (slam) {
        slam->addBeam(beam);
      } else {
        plain->addBeam(beam);
      }
    }
    // Beams are shown and committed in arrival order: those not waiting are the oldest.
    const Clock::time_point now = Clock::now();
    shown.settle(sent.size() - (slam ? slam->beamsUnshown() : plain->beamsUnshown()), now, sent, calibrating);
    committed.settle(sent.size() - (slam ? slam->beamsPending() : plain->beamsPending()), now, sent, calibrating);
  }
  producer.join();
  if (slam) {
    slam->finish();
  } else {
    plain->finish();
  }
  const std::size_t mapped = slam ? slam->mapper().mapper().stats().beams_used : plain->mapper().stats().beams_used;
  std::printf("| %s | %.0f× (%.0f beams/s) | %zu | %.3f | %.3f | %.3f | %zu | %.0f | %.0f | %.0f | %.0f | %zu | %zu |\n",
              c.name, rate, rate / interval_s, shown.latency_ms.size(), percentileOf(shown.latency_ms, 0.5),
              percentileOf(shown.latency_ms, 0.99), maxOf(shown.latency_ms), committed.latency_ms.size(),
              percentileOf(committed.latency_ms, 0.5), percentileOf(committed.latency_ms, 0.99), maxOf(committed.latency_ms),
              percentileOf(shown.warmup_ms, 0.5), late, mapped);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: sonarmap_live_latency LOG [RATE ...]\n");
    return 2;
  }
  try {
    const SonarLog log = readSonarLog(argv[1]);
    std::vector<double> rates;
    for (int i = 2; i < argc; ++i) rates.push_back(std::stod(argv[i]));
    if (rates.empty()) rates = {1.0, 20.0};
    std::vector<std::vector<std::uint8_t>> packets;
    for (const Beam& beam : log.beams) packets.push_back(encodeSeaNetCapture({beam}));
    const double interval_s = beamInterval_s(log);
    std::printf("| model | replay rate | shown: beams | median (ms) | 99th pct (ms) | max (ms) | committed: beams | "
                "median (ms) | 99th pct (ms) | max (ms) | before the first sweep: shown, median (ms) | late | beams "
                "mapped |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    const Case cases[] = {{"planar, 2 cm", BeamModel::kPlanar, 0.02},
                          {"volume, 5 cm", BeamModel::kVolume, 0.05},
                          {"volume, 2 cm", BeamModel::kVolume, 0.02},
                          {"planar, 2 cm, --slam", BeamModel::kPlanar, 0.02, true}};
    for (const Case& c : cases) {
      for (const double rate : rates) replay(packets, interval_s, rate, c);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sonarmap_live_latency: %s\n", error.what());
    return 1;
  }
  return 0;
}
