/// @file bench_octree_rays.cpp
/// Pure ray traversal, no map: the floor that ray insertion cannot beat.
///
/// 100,000 random segments at 5 cm, the same for both libraries: origin uniform in [-5 m, 5 m]³,
/// direction uniform on the sphere, length uniform in [0 m, 10 m]. The end points are generated
/// as float (OctoMap's point3d) and widened to double for sonarmap, so both start from the same
/// numbers. Per iteration, every ray is walked and every key is folded into a checksum (the
/// minimal "use" of a key):
///   BM_OctreeRays/sonarmap_dda          traverseDDA with a visitor: no allocation, no map
///   BM_OctreeRays/sonarmap_dda_vector   rayKeysDDA into a reused std::vector, then the keys read
///   BM_OctreeRays/octomap_computeRayKeys  OcTree::computeRayKeys into a reused KeyRay, then read
///
/// voxels/s counts the keys each library produced: sonarmap visits the end voxel (last), OctoMap's
/// computeRayKeys leaves it out. The OctoMap row also reports rays_identical: the share of rays
/// whose OctoMap keys equal sonarmap's keys without the end voxel, in order.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <octomap/octomap.h>

#include "bench_data.hpp"
#include "sonarmap/core/key_coder.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap::bench {
namespace {

constexpr double kRayResolution_m = 0.05;

struct Segment {
  octomap::point3d origin, end;
  Eigen::Vector3d origin_m, end_m;
};

const std::vector<Segment>& randomSegments() {
  static const std::vector<Segment> segments = [] {
    constexpr std::size_t kRays = 100'000;
    std::mt19937_64 rng(314159);
    std::uniform_real_distribution<double> box(-5.0, 5.0), unit(-1.0, 1.0), length(0.0, 10.0),
        angle(0.0, 2.0 * std::numbers::pi);
    std::vector<Segment> out;
    out.reserve(kRays);
    for (std::size_t i = 0; i < kRays; ++i) {
      const double z = unit(rng), phi = angle(rng), r = std::sqrt(1.0 - z * z), l = length(rng);
      const double ox = box(rng), oy = box(rng), oz = box(rng);
      Segment s;
      s.origin = octomap::point3d(static_cast<float>(ox), static_cast<float>(oy), static_cast<float>(oz));
      s.end = octomap::point3d(static_cast<float>(ox + l * r * std::cos(phi)),
                               static_cast<float>(oy + l * r * std::sin(phi)), static_cast<float>(oz + l * z));
      s.origin_m = {s.origin.x(), s.origin.y(), s.origin.z()};
      s.end_m = {s.end.x(), s.end.y(), s.end.z()};
      out.push_back(s);
    }
    return out;
  }();
  return segments;
}

inline std::uint64_t fold(std::uint64_t sum, std::uint16_t x, std::uint16_t y, std::uint16_t z) {
  return sum + (static_cast<std::uint64_t>(x) | (static_cast<std::uint64_t>(y) << 16) |
                (static_cast<std::uint64_t>(z) << 32));
}

void setRayCounters(benchmark::State& state, std::size_t rays, std::size_t voxels) {
  using benchmark::Counter;
  state.counters["rays"] = Counter(static_cast<double>(rays));
  state.counters["voxels"] = Counter(static_cast<double>(voxels));
  state.counters["voxels/s"] = Counter(static_cast<double>(voxels), Counter::kIsIterationInvariantRate);
}

void BM_OctreeRays_sonarmap(benchmark::State& state, bool to_vector) {
  const std::vector<Segment>& segments = randomSegments();
  const KeyCoder<16> coder(kRayResolution_m);
  std::vector<Key16> keys;
  std::size_t voxels = 0;
  for (auto _ : state) {
    std::uint64_t sum = 0;
    voxels = 0;
    for (const Segment& s : segments) {
      if (to_vector) {
        rayKeysDDA(coder, s.origin_m, s.end_m, keys);
        for (const Key16& key : keys) sum = fold(sum, key[0], key[1], key[2]);
        voxels += keys.size();
      } else {
        traverseDDA(coder, s.origin_m, s.end_m, [&](const Key16& key) {
          sum = fold(sum, key[0], key[1], key[2]);
          ++voxels;
        });
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  setRayCounters(state, segments.size(), voxels);
}

void BM_OctreeRays_octomap(benchmark::State& state) {
  const std::vector<Segment>& segments = randomSegments();
  const octomap::OcTree tree(kRayResolution_m);
  octomap::KeyRay ray;
  std::size_t voxels = 0;
  for (auto _ : state) {
    std::uint64_t sum = 0;
    voxels = 0;
    for (const Segment& s : segments) {
      tree.computeRayKeys(s.origin, s.end, ray);
      for (const octomap::OcTreeKey& key : ray) sum = fold(sum, key[0], key[1], key[2]);
      voxels += ray.size();
    }
    benchmark::DoNotOptimize(sum);
  }
  setRayCounters(state, segments.size(), voxels);

  // Untimed: the same rays through sonarmap, end voxel dropped, compared key by key.
  const KeyCoder<16> coder(kRayResolution_m);
  std::vector<Key16> keys;
  std::size_t identical = 0, sonarmap_voxels = 0;
  for (const Segment& s : segments) {
    tree.computeRayKeys(s.origin, s.end, ray);
    rayKeysDDA(coder, s.origin_m, s.end_m, keys);
    if (!keys.empty()) keys.pop_back();
    sonarmap_voxels += keys.size();
    bool same = keys.size() == ray.size();
    std::size_t i = 0;
    for (auto it = ray.begin(); same && it != ray.end(); ++it, ++i) {
      same = (*it)[0] == keys[i][0] && (*it)[1] == keys[i][1] && (*it)[2] == keys[i][2];
    }
    identical += same ? 1 : 0;
  }
  using benchmark::Counter;
  state.counters["rays_identical"] =
      Counter(static_cast<double>(identical) / static_cast<double>(segments.size()));
  state.counters["voxels_sonarmap_no_end"] = Counter(static_cast<double>(sonarmap_voxels));
}

BENCHMARK_CAPTURE(BM_OctreeRays_sonarmap, dda, false)->Name("BM_OctreeRays/sonarmap_dda")->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeRays_sonarmap, dda_vector, true)->Name("BM_OctreeRays/sonarmap_dda_vector")->Apply(configure);
BENCHMARK(BM_OctreeRays_octomap)->Name("BM_OctreeRays/octomap_computeRayKeys")->Apply(configure);

}  // namespace
}  // namespace sonarmap::bench
