/// @file echo_agreement.cpp
/// echoAgreement (see echo_agreement.hpp).

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/eval/echo_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <nanoflann.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

/// Points for a nanoflann k-d tree (its dataset adaptor interface).
struct PointCloud3 {
  std::vector<Eigen::Vector3d> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t index, std::size_t dim) const { return points[index][static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud3>, PointCloud3, 3>;

/// Per beam of `log`, the intensity count a strong echo must reach at each bin: the median of that
/// bin over the beams of its head setting, plus strong_db in counts.
std::vector<std::vector<float>> strongLevels(const SonarLog& log, double strong_db) {
  std::vector<HeadSetting> settings;
  std::vector<std::size_t> setting_of(log.beams.size());
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const HeadSetting setting = headSettingOf(log.beams[i]);
    const auto known = std::find(settings.begin(), settings.end(), setting);
    setting_of[i] = static_cast<std::size_t>(known - settings.begin());
    if (known == settings.end()) settings.push_back(setting);
  }
  std::vector<std::vector<float>> level_of_setting(settings.size());
  std::vector<std::uint8_t> column;
  for (std::size_t s = 0; s < settings.size(); ++s) {
    std::size_t bins = 0;
    double span_db = kDefaultIntensitySpan_db;
    for (std::size_t i = 0; i < log.beams.size(); ++i) {
      if (setting_of[i] != s) continue;
      bins = std::max(bins, log.beams[i].intensities.size());
      if (log.beams[i].intensity_span_db) span_db = *log.beams[i].intensity_span_db;
    }
    const auto rise = static_cast<float>(countsForDb(strong_db, span_db));
    for (std::size_t c = 0; c < bins; ++c) {
      column.clear();
      for (std::size_t i = 0; i < log.beams.size(); ++i) {
        if (setting_of[i] == s && c < log.beams[i].intensities.size()) column.push_back(log.beams[i].intensities[c]);
      }
      const auto middle = column.begin() + static_cast<std::ptrdiff_t>(column.size() / 2);
      std::nth_element(column.begin(), middle, column.end());
      level_of_setting[s].push_back(static_cast<float>(*middle) + rise);
    }
  }
  std::vector<std::vector<float>> levels(log.beams.size());
  for (std::size_t i = 0; i < log.beams.size(); ++i) levels[i] = level_of_setting[setting_of[i]];
  return levels;
}

/// Whether a point lies within `tolerance_m` of a point of `tree`'s cloud.
bool near(const KdTree& tree, const Eigen::Vector3d& point, double tolerance_m) {
  std::size_t index = 0;
  double distance_sq = 0.0;
  nanoflann::KNNResultSet<double> result(1);
  result.init(&index, &distance_sq);
  tree.findNeighbors(result, point.data(), nanoflann::SearchParams());
  return result.size() > 0 && distance_sq <= tolerance_m * tolerance_m;
}

double share(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

}  // namespace

void EchoAgreementOptions::validate() const {
  if (!(std::isfinite(strong_db) && strong_db > 0.0)) throw ValueError("echo agreement: strong_db must be > 0 dB");
  if (!(std::isfinite(tolerance_m) && tolerance_m > 0.0)) throw ValueError("echo agreement: tolerance_m must be > 0 m");
}

EchoAgreement echoAgreement(const OcTree16& map, const SonarLog& log,
                            const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map,
                            const EchoAgreementOptions& options) {
  options.validate();
  if (!sonar_to_map.empty() && sonar_to_map.size() != log.beams.size()) {
    throw ValueError("echo agreement: " + std::to_string(sonar_to_map.size()) + " poses for " +
                     std::to_string(log.beams.size()) + " beams");
  }
  const std::vector<std::vector<float>> levels = strongLevels(log, options.strong_db);
  PointCloud3 echoes;
  std::vector<std::size_t> first_echoes;  // index in echoes.points of each beam's nearest strong echo
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const Beam& beam = log.beams[i];
    if (!sonar_to_map.empty() && !sonar_to_map[i]) continue;
    const Eigen::Isometry3d pose = sonar_to_map.empty() ? staticSonarToMap() : *sonar_to_map[i];
    const Eigen::Vector3d axis(std::cos(beam.bearing_rad), std::sin(beam.bearing_rad), 0.0);
    bool first = true;
    for (std::size_t c = 0; c < beam.intensities.size(); ++c) {
      if (static_cast<float>(beam.intensities[c]) < levels[i][c]) continue;
      if (first) first_echoes.push_back(echoes.points.size());
      first = false;
      echoes.points.push_back(pose * (axis * ((static_cast<double>(c) + 0.5) * beam.bin_length_m)));
    }
  }
  PointCloud3 occupied;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (!(leaf.log_odds > map.model().occupied_above)) return;
    const double edge_m = leaf.edgeVoxels() * map.resolution_m();
    occupied.points.push_back(map.coder().centerOf(leaf.key) +
                              Eigen::Vector3d::Constant(0.5 * (edge_m - map.resolution_m())));
  });
  EchoAgreement result;
  result.echo_points = echoes.points.size();
  result.beams_with_echo = first_echoes.size();
  result.occupied = occupied.points.size();
  if (echoes.points.empty() || occupied.points.empty()) return result;
  // The constructors build the indices (nanoflann 1.4).
  const KdTree echo_tree(3, echoes, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  const KdTree occupied_tree(3, occupied, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  std::size_t precise = 0, recalled = 0, first_recalled = 0;
  for (const Eigen::Vector3d& voxel : occupied.points) precise += near(echo_tree, voxel, options.tolerance_m) ? 1 : 0;
  std::vector<bool> echo_near(echoes.points.size());
  for (std::size_t p = 0; p < echoes.points.size(); ++p) {
    echo_near[p] = near(occupied_tree, echoes.points[p], options.tolerance_m);
    recalled += echo_near[p] ? 1 : 0;
  }
  for (const std::size_t p : first_echoes) first_recalled += echo_near[p] ? 1 : 0;
  result.precision = share(precise, occupied.points.size());
  result.recall = share(recalled, echoes.points.size());
  result.first_echo_recall = share(first_recalled, first_echoes.size());
  return result;
}

}  // namespace sonarmap
