#include "map_tiles.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sonarmap/io/web_text.hpp"
#include "sonarmap/sonar/png_writer.hpp"

namespace sonarmap::live {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool sameImage(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

}  // namespace

bool BeamFootprint::mayReach(const Eigen::AlignedBox2d& box) const {
  // Points along the segment no farther apart than a quarter of the box's edge, each tested
  // against the box grown by the margin and half that spacing.
  const double edge = box.sizes().minCoeff();
  const double length = (to_m - from_m).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / std::max(edge / 4.0, 1e-3))));
  const double spacing = length / steps;
  const Eigen::Vector2d grow = Eigen::Vector2d::Constant(margin_m + spacing / 2.0);
  const Eigen::AlignedBox2d grown(box.min() - grow, box.max() + grow);
  for (int k = 0; k <= steps; ++k) {
    if (grown.contains(from_m + (to_m - from_m) * (static_cast<double>(k) / steps))) return true;
  }
  return false;
}

void MapTiles::clear() {
  tiles_.clear();
  grid_.reset();
}

TilePicture MapTiles::draw(const TileRequest& request, const Source& source, std::uint64_t version) {
  TilePicture picture;
  picture.z_m = request.z_m;
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(request.half_width_m);
  const Eigen::AlignedBox2d window(request.centre_m - half, request.centre_m + half);
  const auto box3 = [&](const Eigen::AlignedBox2d& box) {
    return Eigen::AlignedBox3d(Eigen::Vector3d(box.min().x(), box.min().y(), request.z_m),
                               Eigen::Vector3d(box.max().x(), box.max().y(), request.z_m));
  };
  double copy_s = 0.0;
  const auto read = [&](const Eigen::AlignedBox2d& box, const ShownMapVisitor& visit) {
    const auto start = std::chrono::steady_clock::now();
    source(box3(box), visit);
    copy_s += secondsSince(start);
  };
  const auto resolution = [&] {  // an empty box: the map's resolution only
    double resolution_m = 0.0;
    read(Eigen::AlignedBox2d(), [&](const OcTree16& map, std::span<const ShownVoxel>) { resolution_m = map.resolution_m(); });
    return resolution_m;
  };
  const auto gridFor = [&](double resolution_m) {
    TileGrid grid;
    grid.resolution_m = resolution_m;
    grid.tile_px = tile_px_;
    const double span_voxels = 2.0 * request.half_width_m / resolution_m + 1.0;
    grid.voxels_per_pixel = std::max(1, static_cast<int>(std::ceil(span_voxels / request.max_side_px)));
    return grid;
  };

  // The tiles to draw: all of them on a new grid or layer, else the new ones and the changed ones.
  std::vector<std::pair<long, long>> wanted, to_draw;
  const auto plan = [&](const TileGrid& g, bool all) {
    wanted.clear();
    to_draw.clear();
    picture.i0 = g.tileOf(window.min().x()), picture.i1 = g.tileOf(window.max().x());
    picture.j0 = g.tileOf(window.min().y()), picture.j1 = g.tileOf(window.max().y());
    const long i0 = picture.i0, i1 = picture.i1, j0 = picture.j0, j1 = picture.j1;
    for (long i = i0; i <= i1; ++i) {
      for (long j = j0; j <= j1; ++j) {
        wanted.emplace_back(i, j);
        const Eigen::AlignedBox2d tile(Eigen::Vector2d(static_cast<double>(i) * g.edge_m(), static_cast<double>(j) * g.edge_m()),
                                       Eigen::Vector2d(static_cast<double>(i + 1) * g.edge_m(), static_cast<double>(j + 1) * g.edge_m()));
        const auto reached = [&] {
          return std::any_of(request.changed.begin(), request.changed.end(),
                             [&](const BeamFootprint& footprint) { return footprint.mayReach(tile); });
        };
        if (all || !tiles_.contains({i, j}) || reached()) to_draw.emplace_back(i, j);
      }
    }
  };
  const auto layerOf = [&](const TileGrid& g) { return static_cast<long>(std::floor(request.z_m / g.resolution_m)); };
  // The tiles kept are those of the same grid and layer; a new grid or layer draws every tile anew.
  bool full = request.full || !grid_;
  TileGrid grid;
  if (grid_) {
    grid = gridFor(grid_->resolution_m);
    if (!(grid == *grid_) || layerOf(grid) != layer_) {
      tiles_.clear();
      full = true;
    }
  }
  // Each tile drawn from its own part of the map, in place: the cost is the leaves of the tiles drawn.
  const auto drawTile = [&](const TileGrid& g, long i, long j) {
    // Shrunk by a tenth of a voxel: the neighbouring tiles' voxels on its edges are not read.
    const Eigen::Vector2d inset = Eigen::Vector2d::Constant(g.resolution_m / 10.0);
    const Eigen::Vector2d low(static_cast<double>(i) * g.edge_m(), static_cast<double>(j) * g.edge_m());
    TileRaster raster;
    read(Eigen::AlignedBox2d(low + inset, low + Eigen::Vector2d::Constant(g.edge_m()) - inset),
         [&](const OcTree16& map, std::span<const ShownVoxel> shown) { raster = rasterizeTile(map, shown, g, i, j, request.z_m); });
    return raster;
  };
  if (!full) {
    plan(grid, false);
    if (!to_draw.empty() && resolution() != grid.resolution_m) full = true;  // the map coarsened
  }
  if (full) {
    grid = gridFor(resolution());
    if (!grid_ || !(grid == *grid_) || layerOf(grid) != layer_) tiles_.clear();
    plan(grid, true);
  }

  // Draw, keep what did not change, encode what did.
  std::map<std::pair<long, long>, std::shared_ptr<const MapTile>> next;
  for (const auto& id : wanted) {
    if (const auto it = tiles_.find(id); it != tiles_.end()) next.emplace(id, it->second);
  }
  for (const auto& [i, j] : to_draw) {
    TileRaster raster = drawTile(grid, i, j);
    ++picture.drawn;
    if (const auto old = next.find({i, j}); old != next.end() && sameImage(old->second->image, raster.image)) continue;
    auto tile = std::make_shared<MapTile>();
    tile->i = i;
    tile->j = j;
    tile->version = version;
    tile->occupied_px = raster.occupied_px;
    tile->free_px = raster.free_px;
    const std::vector<unsigned char> png = encodePng(raster.image);
    tile->png_bytes = png.size();
    tile->png_base64 = base64(png);
    tile->image = std::move(raster.image);
    picture.png_bytes += png.size();
    ++picture.changed;
    next[{i, j}] = std::move(tile);
  }
  tiles_ = std::move(next);
  grid_ = grid;
  layer_ = layerOf(grid);
  picture.grid = grid;
  picture.copy_s = copy_s;
  for (const auto& [id, tile] : tiles_) picture.tiles.push_back(tile);
  return picture;
}

MapRaster composeTiles(const TileGrid& grid, double z_m, const TileList& tiles, const Eigen::Vector2d& fallback_centre_m) {
  MapRaster raster;
  raster.cell_m = grid.cell_m();
  raster.voxels_per_pixel = grid.voxels_per_pixel;
  raster.z_m = z_m;
  // The known pixels' box in grid pixels: column x along map x (north), y along map y (west).
  long x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  bool any = false;
  const long side = grid.tile_px;
  for (const auto& tile : tiles) {
    for (int row = 0; row < tile->image.rows; ++row) {
      const std::uint8_t* line = tile->image.ptr<std::uint8_t>(row);
      for (int col = 0; col < tile->image.cols; ++col) {
        if (line[col] == 128) continue;
        const long px = tile->i * side + (side - 1 - row), py = tile->j * side + (side - 1 - col);
        if (!any) {
          x_lo = x_hi = px;
          y_lo = y_hi = py;
          any = true;
        }
        x_lo = std::min(x_lo, px), x_hi = std::max(x_hi, px), y_lo = std::min(y_lo, py), y_hi = std::max(y_hi, py);
      }
    }
  }
  if (!any) {
    raster.image = cv::Mat(1, 1, CV_8U, cv::Scalar(128));
    raster.north_m = fallback_centre_m.x() + raster.cell_m / 2.0;
    raster.west_m = fallback_centre_m.y() + raster.cell_m / 2.0;
    return raster;
  }
  --x_lo, ++x_hi, --y_lo, ++y_hi;  // one unknown pixel around the known ones
  raster.image = cv::Mat(static_cast<int>(x_hi - x_lo + 1), static_cast<int>(y_hi - y_lo + 1), CV_8U, cv::Scalar(128));
  for (const auto& tile : tiles) {
    for (int row = 0; row < tile->image.rows; ++row) {
      const std::uint8_t* line = tile->image.ptr<std::uint8_t>(row);
      for (int col = 0; col < tile->image.cols; ++col) {
        const long px = tile->i * side + (side - 1 - row), py = tile->j * side + (side - 1 - col);
        if (px < x_lo || px > x_hi || py < y_lo || py > y_hi) continue;
        raster.image.at<std::uint8_t>(static_cast<int>(x_hi - px), static_cast<int>(y_hi - py)) = line[col];
      }
    }
  }
  for (int row = 0; row < raster.image.rows; ++row) {
    const std::uint8_t* line = raster.image.ptr<std::uint8_t>(row);
    for (int col = 0; col < raster.image.cols; ++col) {
      raster.occupied_px += line[col] == 0;
      raster.free_px += line[col] == 255;
    }
  }
  raster.north_m = static_cast<double>(x_hi + 1) * raster.cell_m;
  raster.west_m = static_cast<double>(y_hi + 1) * raster.cell_m;
  return raster;
}

}  // namespace sonarmap::live
