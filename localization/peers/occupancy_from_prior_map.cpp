#include "localization/peers/occupancy_from_prior_map.hpp"

#include <algorithm>

#include "maps/prior_map/prior_map_region.hpp"

namespace flat2d::localization::peers {
namespace {

constexpr float kOccupied = 0.05f;  // p(free)
constexpr float kFree = 0.95f;
constexpr float kUnknown = 0.5f;

}  // namespace

Result<mrpt::maps::COccupancyGridMap2D::Ptr> OccupancyFromPriorMap(maps::PriorMapReader& map, double resolution_m,
                                                                  OccupancyStats* stats) {
  if (!(resolution_m > 0.0)) return MakeError("the occupancy resolution must be positive");
  const std::optional<maps::MapRegion> extent = maps::StoredExtent(map);
  if (!extent) return MakeError("the map has no stored cells");
  auto region = maps::ReadRegion(map, *extent);
  if (!region.ok()) return region.error();
  const maps::GridGeometry& g = region->geometry();

  auto grid = mrpt::maps::COccupancyGridMap2D::Create(
      static_cast<float>(g.origin.x()), static_cast<float>(g.origin.x() + g.width * g.resolution_m),
      static_cast<float>(g.origin.y()), static_cast<float>(g.origin.y() + g.height * g.resolution_m),
      static_cast<float>(resolution_m));
  grid->fill(kUnknown);
  // Strongest class per occupancy cell: any structure makes it occupied.
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      const maps::CellClass cell = region->at({col, row});
      if (cell == maps::CellClass::kUnknown) continue;
      const Eigen::Vector2d centre = g.CellCenter({col, row});
      const int cx = grid->x2idx(centre.x());
      const int cy = grid->y2idx(centre.y());
      if (cx < 0 || cy < 0 || cx >= static_cast<int>(grid->getSizeX()) || cy >= static_cast<int>(grid->getSizeY())) {
        continue;
      }
      if (cell == maps::CellClass::kSlammable) {
        grid->setCell(cx, cy, kOccupied);
      } else if (grid->getCell(cx, cy) > kOccupied) {
        grid->setCell(cx, cy, kFree);
      }
    }
  }
  if (stats != nullptr) {
    *stats = {};
    stats->cells = static_cast<std::size_t>(grid->getSizeX()) * grid->getSizeY();
    for (unsigned cy = 0; cy < grid->getSizeY(); ++cy) {
      for (unsigned cx = 0; cx < grid->getSizeX(); ++cx) {
        const float p = grid->getCell(static_cast<int>(cx), static_cast<int>(cy));
        if (p < 0.25f) ++stats->occupied;
        else if (p > 0.75f) ++stats->free;
      }
    }
  }
  return grid;
}

}  // namespace flat2d::localization::peers
