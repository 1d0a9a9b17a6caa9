#pragma once
/// @file colour_scale.hpp
/// Values on a colour scale through one of OpenCV's colour maps (cv::applyColorMap's 256-entry
/// tables): the heights of the 3D views (map_views.hpp) and the figures' colour bars and surface
/// errors (render/).

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace sonarmap {

/// The BGR colour of `value` on a scale from `min` to `max` through `colormap` (values outside
/// are clamped; the middle colour when min >= max). Units are the caller's (metres for heights).
cv::Vec3b colourOnScale(cv::ColormapTypes colormap, double value, double min, double max);

}  // namespace sonarmap
