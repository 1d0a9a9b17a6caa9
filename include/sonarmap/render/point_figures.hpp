#pragma once
/// @file point_figures.hpp
/// Point clouds in the horizontal plane drawn side by side on one extent, each with a track: the
/// same scans placed by different trajectories (the dead reckoning, a localization, the truth), so
/// that a wall drawn twice in one panel and once in another shows which trajectory is right.
/// Drawn as figure.hpp's figures (east to the right, north up, axes in metres).

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// One panel: points and a track, NED's plane (x north, y east), metres.
struct PointPanel {
  std::string title;
  std::vector<Eigen::Vector2d> points_ned_m;
  std::vector<Eigen::Vector2d> track_ned_m;  ///< drawn as a red line labelled `track_label`
  std::string track_label = "vehicle";
};

/// A panel titled `title` of `points_ned_m` (NED's plane, metres) with the horizontal positions of
/// `track`'s fixes as its track (NED, metres; the fixes' depths and attitudes are not drawn).
PointPanel pointPanel(std::string title, std::vector<Eigen::Vector2d> points_ned_m, const NavTrack& track);

/// The most cells a point panel spans along its longer side: a finer cell is coarsened to it, so
/// that a small cell over a wide survey, or one point far off, cannot ask for gigabytes of raster.
inline constexpr int kMaxPointPanelCells = 4000;

/// The cell pointPanelsFigure draws `panels` on, metres: `cell_m`, or coarser where the extent of
/// every panel's finite points would span more than kMaxPointPanelCells cells along its longer side.
/// @throws ValueError for no panel, no point in any panel, or a cell that is not finite and > 0.
double pointFigureCell(const std::vector<PointPanel>& panels, double cell_m);

/// The panels side by side (BGR, CV_8UC3), all on the extent of every panel's points, on a grid of
/// pointFigureCell(panels, cell_m): a cell's grey level by how many points fall in it (one point
/// light grey, eight or more black), so a surface seen from several places is dark where they agree.
/// @throws ValueError as pointFigureCell.
cv::Mat pointPanelsFigure(const std::vector<PointPanel>& panels, double cell_m = 0.25);

}  // namespace sonarmap
