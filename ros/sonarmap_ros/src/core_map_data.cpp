/// @file core_map_data.cpp
/// The map as octomap_server's topics carry it (core_internal.hpp).

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "core_internal.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/io/octomap_full.hpp"
#include "sonarmap/mapping/map_slice.hpp"

namespace sonarmap_ros {

std::vector<std::int8_t> octomapData(const sonarmap::OcTree16& map, bool binary) {
  std::ostringstream out;
  if (binary) {
    sonarmap::writeBinary(map, out);
  } else {
    sonarmap::writeFull(map, out);
  }
  const std::string file = out.str();
  // OctoMap's header ends with the line "data" (octomap_header.hpp); the tree's data follows it.
  const std::size_t line = file.find("\ndata\n");
  if (line == std::string::npos) throw sonarmap::Error("octomap data: the written map has no data line");
  const std::size_t begin = line + 6;
  std::vector<std::int8_t> bytes(file.size() - begin);
  if (!bytes.empty()) std::memcpy(bytes.data(), file.data() + begin, bytes.size());
  return bytes;
}

MapData mapData(const sonarmap::OcTree16& map, const CoreParameters& parameters, double vehicle_z_m) {
  MapData data;
  data.resolution_m = map.resolution_m();
  data.binary_data = octomapData(map, true);
  data.full_data = octomapData(map, false);
  // Occupied leaves (log-odds > 0: OctoMap's isNodeOccupied at 0.5) and, when asked, free ones by size,
  // coarsest first; a leaf is in the z band when it reaches into it, as octomap_server's publishAll
  // takes occupancy_min_z/max_z (z + edge/2 > min and z - edge/2 < max).
  std::map<int, MapData::Cells> occupied, free;
  const double res = map.resolution_m(), offset = sonarmap::KeyCoder<16>::offset();
  map.forEachLeaf([&](const sonarmap::LeafView<16>& leaf) {
    const bool is_occupied = leaf.log_odds > 0.0f;
    if (!is_occupied && !parameters.free_cells) return;
    const double edge_m = leaf.edgeVoxels() * res, half_m = 0.5 * edge_m;
    const Eigen::Vector3d center((leaf.key[0] - offset) * res + half_m, (leaf.key[1] - offset) * res + half_m,
                                 (leaf.key[2] - offset) * res + half_m);
    if (center.z() + half_m <= parameters.occupancy_min_z_m || center.z() - half_m >= parameters.occupancy_max_z_m) return;
    MapData::Cells& cells = (is_occupied ? occupied : free)[leaf.depth];
    cells.edge_m = edge_m;
    cells.centers.push_back(center.cast<float>());
  });
  for (auto& [depth, cells] : occupied) data.occupied.push_back(std::move(cells));
  for (auto& [depth, cells] : free) data.free.push_back(std::move(cells));
  // projected_map: the slice at the vehicle's height (map_slice.hpp), as an OccupancyGrid's rows.
  sonarmap::SliceView slice;
  try {
    slice = sonarmap::renderSliceView(map, vehicle_z_m);
  } catch (const sonarmap::Error&) {
    return data;  // the vehicle outside the map: nothing to project
  }
  if (slice.image.empty()) return data;
  data.grid_width = static_cast<std::uint32_t>(slice.image.cols);
  data.grid_height = static_cast<std::uint32_t>(slice.image.rows);
  data.grid_x_m = slice.left_m;
  data.grid_y_m = slice.bottom_m;
  data.grid_z_m = vehicle_z_m;
  data.grid.resize(static_cast<std::size_t>(slice.image.cols) * static_cast<std::size_t>(slice.image.rows));
  // The slice's image has +y up (row 0 the highest y), occupied 0, free 255, unknown 128.
  for (int row = 0; row < slice.image.rows; ++row) {
    const std::size_t grid_row = static_cast<std::size_t>(slice.image.rows - 1 - row);
    for (int col = 0; col < slice.image.cols; ++col) {
      const std::uint8_t pixel = slice.image.at<std::uint8_t>(row, col);
      data.grid[grid_row * static_cast<std::size_t>(slice.image.cols) + static_cast<std::size_t>(col)] =
          pixel == 0 ? 100 : pixel == 255 ? 0 : -1;
    }
  }
  return data;
}

}  // namespace sonarmap_ros
