#include "localization/peers/structure_scan.hpp"

#include <cmath>
#include <numbers>

namespace flat2d::localization::peers {

double RayBearing(int index, int rays) {
  return -std::numbers::pi + 2.0 * std::numbers::pi * index / (rays - 1);
}

int StructureScan(const maps::ClassGrid& grid, const StructureScanOptions& options,
                  mrpt::obs::CObservation2DRangeScan& scan) {
  const int rays = options.rays;
  scan.aperture = static_cast<float>(2.0 * std::numbers::pi);
  scan.rightToLeft = true;
  scan.maxRange = options.max_range_m;
  scan.sensorPose = mrpt::poses::CPose3D();  // the grid's frame is the vehicle's
  scan.resizeScan(static_cast<std::size_t>(rays));
  for (int i = 0; i < rays; ++i) {
    scan.setScanRange(static_cast<std::size_t>(i), options.max_range_m);
    scan.setScanRangeValidity(static_cast<std::size_t>(i), false);
  }

  const maps::GridGeometry& g = grid.geometry();
  const double step = 2.0 * std::numbers::pi / (rays - 1);
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (grid.at({col, row}) != maps::CellClass::kSlammable) continue;
      const Eigen::Vector2d p = g.CellCenter({col, row});
      const auto range = static_cast<float>(p.norm());
      if (range < options.min_range_m || range >= options.max_range_m) continue;
      const auto ray = static_cast<std::size_t>(std::lround((std::atan2(p.y(), p.x()) + std::numbers::pi) / step));
      if (ray >= static_cast<std::size_t>(rays)) continue;
      if (!scan.getScanRangeValidity(ray) || range < scan.getScanRange(ray)) {
        scan.setScanRange(ray, range);
        scan.setScanRangeValidity(ray, true);
      }
    }
  }
  int returns = 0;
  for (int i = 0; i < rays; ++i) returns += scan.getScanRangeValidity(static_cast<std::size_t>(i)) ? 1 : 0;
  return returns;
}

}  // namespace flat2d::localization::peers
