#include "localization/localizer/map_window.hpp"

#include <algorithm>
#include <cmath>

#include "maps/grid/cell_class.hpp"

namespace flat2d::localization {

Status ValidateOptions(const MapWindowOptions& options) {
  if (!(options.side_m > 0.0) || !std::isfinite(options.side_m)) return MakeError("map window side_m must be positive");
  if (!(options.recentre_m >= 0.0) || !(options.recentre_m < options.side_m / 2.0)) {
    return MakeError("map window recentre_m must be in [0, side_m / 2)");
  }
  return Status::Ok();
}

Result<MapWindow> MapWindow::Create(const maps::PriorMapReader& map, const MapWindowOptions& options) {
  if (Status valid = ValidateOptions(options); !valid.ok()) return valid.error();
  GridGeometry geometry;
  geometry.resolution = map.header().resolution_m();
  geometry.width = geometry.height = static_cast<int>(std::ceil(options.side_m / geometry.resolution));
  geometry.origin = Eigen::Vector2d(map.header().origin_x_m(), map.header().origin_y_m());
  if (Status valid = ValidateGeometry(geometry); !valid.ok()) return valid.error();
  return MapWindow(options, geometry);
}

MapWindow::MapWindow(const MapWindowOptions& options, const GridGeometry& geometry)
    : options_(options), grid_(geometry) {}

Result<bool> MapWindow::Cover(maps::PriorMapReader& map, const Eigen::Vector2d& position) {
  return Cover(map, position, options_.recentre_m);
}

Result<bool> MapWindow::Cover(maps::PriorMapReader& map, const Eigen::Vector2d& position, double max_offset_m) {
  if (filled_ && (position - centre_).norm() < max_offset_m) return false;
  ++moves_;
  if (Status filled = Fill(map, position); !filled.ok()) return filled.error();
  return true;
}

Result<bool> MapWindow::CoverWithViewpoint(maps::PriorMapReader& map, const Eigen::Vector2d& position,
                                           double switch_margin_m) {
  const auto& viewpoints = map.header().viewpoints();
  int nearest = -1;
  double nearest_m = 0.0, current_m = 0.0;
  for (int i = 0; i < viewpoints.size(); ++i) {
    const double d = (Eigen::Vector2d(viewpoints[i].x_m(), viewpoints[i].y_m()) - position).norm();
    if (nearest < 0 || d < nearest_m) {
      nearest = i;
      nearest_m = d;
    }
    if (i == viewpoint_) current_m = d;
  }
  if (nearest < 0) return false;
  if (filled_ && viewpoint_ >= 0 && (nearest == viewpoint_ || nearest_m > current_m - switch_margin_m)) return false;
  ++moves_;
  if (Status filled = FillViewpoint(map, nearest); !filled.ok()) return filled.error();
  return true;
}

Status MapWindow::FillViewpoint(maps::PriorMapReader& map, int index) {
  const auto& header = map.header();
  const maps::Viewpoint& v = header.viewpoints(index);
  const Eigen::Vector2d map_origin(header.origin_x_m(), header.origin_y_m());
  grid_.Reset(map_origin + header.resolution_m() * Eigen::Vector2d(v.col(), v.row()));
  filled_ = false;
  viewpoint_ = -1;
  auto cells = map.ViewpointCells(index);
  if (!cells.ok()) return cells.error();
  constexpr auto kSlammable = static_cast<std::uint8_t>(maps::CellClass::kSlammable);
  const int width = std::min(v.width(), grid_.width()), height = std::min(v.height(), grid_.height());
  for (int row = 0; row < height; ++row) {
    const std::uint8_t* block_row = cells->data() + static_cast<std::size_t>(row) * v.width();
    for (int col = 0; col < width; ++col) {
      if (block_row[col] == kSlammable) grid_.SetOccupied(col, row);
    }
  }
  centre_ = Eigen::Vector2d(v.x_m(), v.y_m());
  viewpoint_ = index;
  filled_ = true;
  return Status::Ok();
}

Status MapWindow::Fill(maps::PriorMapReader& map, const Eigen::Vector2d& centre) {
  const auto& header = map.header();
  const double resolution = header.resolution_m();
  const Eigen::Vector2d map_origin(header.origin_x_m(), header.origin_y_m());
  const int side = grid_.width();
  // The window's first cell, in map cells (may be negative: off the map is empty).
  const Eigen::Vector2d first = ((centre - map_origin) / resolution).array().floor() - side / 2;
  const int first_col = static_cast<int>(first.x());
  const int first_row = static_cast<int>(first.y());
  grid_.Reset(map_origin + resolution * Eigen::Vector2d(first_col, first_row));
  filled_ = false;
  viewpoint_ = -1;
  centre_ = centre;

  const int n = header.tile_cells();
  const auto tile_of = [n](int cell) { return cell >= 0 ? cell / n : -((-cell + n - 1) / n); };
  constexpr auto kSlammable = static_cast<std::uint8_t>(maps::CellClass::kSlammable);
  for (int tile_row = tile_of(first_row); tile_row <= tile_of(first_row + side - 1); ++tile_row) {
    for (int tile_col = tile_of(first_col); tile_col <= tile_of(first_col + side - 1); ++tile_col) {
      auto cells = map.Tile(tile_col, tile_row);
      if (!cells.ok()) return cells.error();
      // The tile's cells that fall in the window, in map cells.
      const int col_begin = std::max(tile_col * n, first_col), col_end = std::min((tile_col + 1) * n, first_col + side);
      const int row_begin = std::max(tile_row * n, first_row), row_end = std::min((tile_row + 1) * n, first_row + side);
      for (int row = row_begin; row < row_end; ++row) {
        const std::uint8_t* tile_row_cells = cells->data() + static_cast<std::size_t>(row - tile_row * n) * n;
        for (int col = col_begin; col < col_end; ++col) {
          if (tile_row_cells[col - tile_col * n] == kSlammable) grid_.SetOccupied(col - first_col, row - first_row);
        }
      }
    }
  }
  filled_ = true;
  return Status::Ok();
}

}  // namespace flat2d::localization
