// Pictures of a map for notebooks: the images `sonarmap map` writes as PNGs (map_slice.hpp's slice at
// z = 0, map_views.hpp's top and side views of a 3D map) as numpy arrays, and a slice's cells.
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <pybind11/numpy.h>

#include "bindings.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/sonar/map_views.hpp"

namespace sonarmap::python {
namespace {

/// A CV_8U or CV_8UC3 image as a numpy array that owns it (no copy of the pixels).
py::array imageArray(cv::Mat image) {
  auto* owned = new cv::Mat(image.isContinuous() ? image : image.clone());
  py::capsule owner(owned, [](void* p) { delete static_cast<cv::Mat*>(p); });
  std::vector<py::ssize_t> shape{owned->rows, owned->cols};
  std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(owned->step[0]), owned->channels()};
  if (owned->channels() > 1) {
    shape.push_back(owned->channels());
    strides.push_back(1);
  }
  return py::array_t<std::uint8_t>(shape, strides, owned->ptr<std::uint8_t>(), owner);
}

py::dict viewDict(const MapView& view) {
  cv::Mat rgb;
  cv::cvtColor(view.image, rgb, cv::COLOR_BGR2RGB);
  py::dict out;
  out["image"] = imageArray(rgb);
  out["view_cols"] = view.view_cols;
  out["view_rows"] = view.view_rows;
  out["pixels_per_voxel"] = view.pixels_per_voxel;
  out["scale_min_m"] = view.scale_min_m;
  out["scale_max_m"] = view.scale_max_m;
  out["occupied_pixels"] = view.occupied_pixels;
  return out;
}

Occupancy occupancyNamed(const std::string& name) {
  if (name == "occupied") return Occupancy::kOccupied;
  if (name == "free") return Occupancy::kFree;
  if (name == "unknown") return Occupancy::kUnknown;
  throwValueError("occupancy expects 'occupied', 'free' or 'unknown', got '" + name + "'");
}

}  // namespace

void bindViews(py::module_& m) {
  py::class_<OccupancyMap> cls(m.attr("OccupancyMap"));  // bound in bind_map.cpp
  cls.def(
         "slice_cells",
         [](const OccupancyMap& map, double z_m, const std::string& occupancy) {
           std::vector<Eigen::Vector2d> cells;
           {
             py::gil_scoped_release release;
             cells = cellsInSlice(map.tree, z_m, occupancyNamed(occupancy));
           }
           py::array_t<double> out({static_cast<py::ssize_t>(cells.size()), py::ssize_t{2}});
           auto view = out.mutable_unchecked<2>();
           for (std::size_t i = 0; i < cells.size(); ++i) {
             view(i, 0) = cells[i].x();
             view(i, 1) = cells[i].y();
           }
           return out;
         },
         py::arg("z_m") = 0.0, py::arg("occupancy") = "occupied",
         R"doc(Centres (x, y) of the finest voxels of the horizontal slice holding height ``z_m`` (metres, map
frame) whose class is ``occupancy`` ("occupied", "free" or "unknown"): float64 (K, 2), metres.
Pruned leaves count as each of their voxels. The 2D map of the planar model is the slice z = 0
(paper §6). Raises sonarmap.OutOfMapError when z_m is outside the map.)doc")
      .def(
          "render_slice",
          [](const OccupancyMap& map, double z_m) {
            cv::Mat image;
            {
              py::gil_scoped_release release;
              image = renderSlice(map.tree, z_m);
            }
            return imageArray(image);
          },
          py::arg("z_m") = 0.0,
          R"doc(The slice at ``z_m`` as ``sonarmap map --png`` draws it for a planar map: uint8 (rows, cols), one
pixel per voxel, occupied 0, free 255, unknown 128; +x to the right, +y UP (row 0 is the top);
spanning the slice's known voxels plus a one-voxel border. Raises sonarmap.OutOfMapError.)doc")
      .def(
          "render_top_view",
          [](const OccupancyMap& map, int max_side_px) {
            MapView view;
            {
              py::gil_scoped_release release;
              view = renderTopView(map.tree, max_side_px);
            }
            return viewDict(view);
          },
          py::arg("max_side_px") = 0,
          R"doc(Top view of a 3D map (``sonarmap map --3d --png``): each (x, y) column's highest occupied voxel
coloured by its height (viridis), free columns light grey, unknown white, a legend panel on the
right. Returns a dict: image uint8 (rows, cols, 3) RGB; view_cols, view_rows (the view without
the legend, pixels); pixels_per_voxel; scale_min_m, scale_max_m (the colour scale's ends, metres
of z); occupied_pixels. +x to the right, +y up. max_side_px > 0 magnifies up to that size.)doc")
      .def(
          "render_side_view",
          [](const OccupancyMap& map, int max_side_px) {
            MapView view;
            {
              py::gil_scoped_release release;
              view = renderSideView(map.tree, max_side_px);
            }
            return viewDict(view);
          },
          py::arg("max_side_px") = 0,
          R"doc(Side view of a 3D map (``sonarmap map --side-png``), looking along +y: +x to the right, +z up,
each occupied voxel nearest the viewer coloured by its y (metres). Returns the dict of
render_top_view (its scale in metres of y).)doc");
}

}  // namespace sonarmap::python
