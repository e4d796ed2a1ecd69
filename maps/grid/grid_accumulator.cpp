#include "maps/grid/grid_accumulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flat2d::maps {

namespace {

void Increment(std::uint16_t& count) {
  if (count < std::numeric_limits<std::uint16_t>::max()) ++count;
}

}  // namespace

GridAccumulator::GridAccumulator(const GridGeometry& world, const AccumulationOptions& options)
    : geometry_(world), options_(options), votes_(world.cell_count()) {}

void GridAccumulator::Add(const ClassGrid& grid, const Eigen::Isometry2d& world_T_grid) {
  const GridGeometry& g = grid.geometry();
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      const CellClass cell_class = grid.at({col, row});
      if (cell_class == CellClass::kUnknown) continue;
      const auto world = geometry_.CellOf(world_T_grid * g.CellCenter({col, row}));
      if (!world) continue;
      Votes& votes = votes_[geometry_.Offset(*world)];
      Increment(votes.observed);
      if (cell_class == CellClass::kHazard || cell_class == CellClass::kSlammable) Increment(votes.hazard);
      if (cell_class == CellClass::kSlammable) Increment(votes.slammable);
    }
  }
  ++revolutions_;
}

ClassGrid GridAccumulator::Result() const {
  ClassGrid result(geometry_);
  auto enough = [&](int votes, int observed) {
    return votes >= options_.min_structure_votes && votes >= options_.min_structure_fraction * observed;
  };
  for (int row = 0; row < geometry_.height; ++row) {
    for (int col = 0; col < geometry_.width; ++col) {
      const Votes& votes = votes_[geometry_.Offset({col, row})];
      if (votes.observed == 0) continue;
      CellClass cell_class = CellClass::kFree;
      if (enough(votes.slammable, votes.observed)) {
        cell_class = CellClass::kSlammable;
      } else if (enough(votes.hazard, votes.observed)) {
        cell_class = CellClass::kHazard;
      }
      result.Mark(CellIndex{col, row}, cell_class);
    }
  }
  return result;
}

GridGeometry GeometryAround(const std::vector<Eigen::Vector2d>& positions, double margin_m, double resolution_m) {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
  if (!positions.empty()) {
    lo = hi = positions.front();
    for (const Eigen::Vector2d& p : positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  lo.array() -= margin_m;
  hi.array() += margin_m;
  // Origins on whole cells keep grids of one drive aligned with each other.
  const Eigen::Vector2d origin = (lo / resolution_m).array().floor() * resolution_m;
  return GridGeometry{.width = static_cast<int>(std::ceil((hi.x() - origin.x()) / resolution_m)),
                      .height = static_cast<int>(std::ceil((hi.y() - origin.y()) / resolution_m)),
                      .resolution_m = resolution_m,
                      .origin = origin};
}

}  // namespace flat2d::maps
