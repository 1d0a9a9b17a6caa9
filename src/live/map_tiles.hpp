#pragma once
/// @file map_tiles.hpp
/// The live page's map as tiles (map_raster.hpp's TileGrid): the tiles meeting the window around
/// the vehicle, each drawn and PNG-encoded once per change whatever the number of pages, and
/// redrawn only where the map changed. Internal to sonarmap::live (LiveView's raster thread).
///
/// Frames: the map frame (NWU, metres). Not thread-safe: one thread draws; the tiles it hands out
/// are immutable and may be read from any thread.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "sonarmap/live/map_raster.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::live {

using TileList = std::vector<std::shared_ptr<const MapTile>>;

/// The part of the map one beam may have changed: the points within margin_m of the segment from
/// its sonar to its reach (map x, y, metres).
struct BeamFootprint {
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero(), to_m = Eigen::Vector2d::Zero();
  double margin_m = 0.0;
  /// Whether it may reach the box (conservative: true for some boxes slightly farther than margin_m).
  bool mayReach(const Eigen::AlignedBox2d& box) const;
};

/// What one picture asks for.
struct TileRequest {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();  ///< the window's centre, map x, y, metres
  double half_width_m = 50.0;                          ///< > 0
  double z_m = 0.0;                                    ///< the layer's height, map z, metres
  int max_side_px = 2560;  ///< RasterWindow::max_side_px: the grid's pixels hold k × k voxels beyond it
  bool full = false;       ///< redraw every tile of the window
  /// What the beams shown since the last picture may have changed; every tile they may reach is
  /// drawn again.
  std::vector<BeamFootprint> changed;
};

/// What a picture made.
struct TilePicture {
  TileGrid grid;
  double z_m = 0.0;
  TileList tiles;              ///< every tile meeting the window, by (i, j)
  long i0 = 0, i1 = -1, j0 = 0, j1 = -1;  ///< the window's tiles: i0 … i1 × j0 … j1
  std::size_t drawn = 0;       ///< tiles drawn again
  std::size_t changed = 0;     ///< of which changed (a new version, encoded)
  std::size_t png_bytes = 0;   ///< of the changed tiles' PNGs
  double copy_s = 0.0;         ///< in the map source's calls (reading the map under its lock), seconds
};

class MapTiles {
 public:
  /// Reads the map as shown in a box (map frame, metres), as OnlineMapper::visitShown.
  using Source = std::function<void(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit)>;

  explicit MapTiles(int tile_px = 32) : tile_px_(tile_px) {}

  /// Draws the tiles of the window that are new, that request.changed may reach, or all of them when
  /// request.full, the grid changed (the map's resolution, or the pixel size the window needs) or
  /// the layer did; a tile drawn the same as before keeps its version. Tiles that left the window
  /// are dropped. `version` is given to the tiles that changed.
  /// @throws what `source` and rasterizeTile throw (the tiles stay as they were).
  TilePicture draw(const TileRequest& request, const Source& source, std::uint64_t version);
  /// Forgets every tile (a reset map).
  void clear();

 private:
  int tile_px_;
  std::optional<TileGrid> grid_;
  long layer_ = 0;  ///< the layer's voxel index (floor(z / resolution))
  std::map<std::pair<long, long>, std::shared_ptr<const MapTile>> tiles_;
};

/// The tiles put together, as rasterizeMap's picture: cropped to their known pixels plus a border
/// of one unknown pixel (1 × 1 unknown at `fallback_centre_m` when none is known).
MapRaster composeTiles(const TileGrid& grid, double z_m, const TileList& tiles, const Eigen::Vector2d& fallback_centre_m);

}  // namespace sonarmap::live
