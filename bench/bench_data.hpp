#pragma once
/// @file bench_data.hpp
/// Inputs shared by the benchmarks: the CRAS Micron log (read once), a synthetic tank log that
/// needs no file, the mapper variants, and sweeps prepared (preprocessed and detected) once so
/// later stages can be timed alone.

#include <cstddef>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/detection/detection.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap::bench {

/// Where a benchmark's beams come from.
enum class Source {
  kCras,       ///< ../shared/data/cras_micron_tank_static.mat (28 sweeps of 200 beams, 399 bins)
  kSynthetic,  ///< syntheticTankLog(): runs without any data file
};

/// Mapper configurations compared by the benchmarks.
enum class Variant {
  kDefault,    ///< MapperOptions{}: DDA, 3° beam fan, lazy octree (what the CLI runs)
  kSingleRay,  ///< beam_width_rad = 0: one ray per beam along its bearing (paper §6)
  kBresenham,  ///< 3D Bresenham instead of DDA, 3° fan
  kEager,      ///< non-lazy octree: inner nodes updated and pruned on every update
};

/// MapperOptions of a variant.
MapperOptions mapperOptions(Variant variant);

/// The beam-volume model: MapperOptions{} with beam_model = BeamModel::kVolume and
/// `resolution_m` set, every other option at its default (the Micron's 3° × 35° cone, the default
/// free aperture and arc evidence, detection pipelined unless `pipeline_detection` is false).
MapperOptions volumeOptions(double resolution_m, bool pipeline_detection = true);

/// Path of the CRAS log: $SONARMAP_DATA (a folder) if set, else the SONARMAP_SHARED_DATA folder
/// given at compile time, joined with cras_micron_tank_static.mat.
std::string crasPath();

/// The log of `source`, read or generated once per process, or nullptr when it cannot be had.
/// @param error set to the reason (missing file, reader's message) when nullptr is returned.
const SonarLog* sourceLog(Source source, std::string& error);

/// Like sourceLog(), but calls state.SkipWithError and returns nullptr when the log is missing.
const SonarLog* logOrSkip(benchmark::State& state, Source source);

/// 28 sweeps of 200 beams (1.8° steps, first bearing 0), 399 bins of 1.25 cm, seen from inside a
/// 4.2 m × 4.2 m square tank off-centre of the sonar: speckle, the vehicle's self-reflection band
/// (first 0.3 m) and a wall echo of 12 bins at the wall's range. Deterministic.
SonarLog syntheticTankLog();

/// Sweeps of a log as mapSonarLog() forms them, each calibrated, cleaned and searched as
/// SonarMapper::detectSweep does with `options`.
struct PreparedSweeps {
  std::vector<PolarImage> polar;                      ///< one cleaned image per sweep
  std::vector<std::vector<BeamDetection>> detections;  ///< one per row of polar[i]
  std::size_t beams = 0;                              ///< rows over all sweeps
};

/// Raw (not yet preprocessed) polar images of the sweeps mapSonarLog() would map.
std::vector<PolarImage> rawSweeps(const SonarLog& log, const MapperOptions& options);

/// rawSweeps(), calibrated, cleaned and detected as SonarMapper::mapSweep does.
PreparedSweeps prepareSweeps(const SonarLog& log, const MapperOptions& options);

/// The beams of one sweep as SonarMapper::integrateSweep hands them to planSweep
/// (sonarmap/mapping/sweep_fan.hpp), with the sonar static at the map origin and no range
/// tolerance: an obstacle beam is free up to its obstacle, any other beam up to its water range.
/// `beams` is cleared first.
void sweepBeams(const PolarImage& polar, const std::vector<BeamDetection>& detections, std::vector<PlannedBeam>& beams);

/// Settings of every benchmark: milliseconds, and a "min" statistic beside Google Benchmark's
/// mean/median/stddev/cv when run with --benchmark_repetitions (the least disturbed repetition,
/// useful on a shared machine). Use as BENCHMARK(...)->Apply(configure).
void configure(benchmark::internal::Benchmark* benchmark);

/// Sets the counters every mapping benchmark reports: sweeps, beams/s, map nodes, leaves and map
/// bytes (`nodes`, `leaves`, `bytes` of the map of the last iteration).
void setMapCounters(benchmark::State& state, std::size_t sweeps, std::size_t beams, std::size_t nodes,
                    std::size_t leaves, std::size_t bytes);

}  // namespace sonarmap::bench
