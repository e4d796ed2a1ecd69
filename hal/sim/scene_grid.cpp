#include "hal/sim/scene_grid.hpp"

#include <functional>

#include "hal/sim/scene_footprint.hpp"

namespace flat2d::hal::sim::internal {
namespace {

// Footprints are grown by this much when filed, so a ray whose cell index rounds the
// wrong way at a cell boundary still finds every solid there.
constexpr double kFilingSlack = 1e-6;

using OverlapTest = std::function<bool(const Eigen::AlignedBox2d&)>;

struct CellLists {
  Eigen::Vector2d origin;
  double cell = 1.0;
  int nx = 0;
  int ny = 0;
  std::vector<std::vector<std::uint32_t>> lists;
  std::vector<double> top_z;

  // Files `ref` under every cell within `bounds` that `overlaps` accepts.
  void File(std::uint32_t ref, Eigen::AlignedBox2d bounds, double top, const OverlapTest& overlaps) {
    const Eigen::Vector2d slack = Eigen::Vector2d::Constant(kFilingSlack);
    bounds = Eigen::AlignedBox2d(bounds.min() - slack, bounds.max() + slack);
    const auto index = [&](double v, double o, int n) {
      return std::clamp(static_cast<int>(std::floor((v - o) / cell)), 0, n - 1);
    };
    const int x0 = index(bounds.min().x(), origin.x(), nx);
    const int x1 = index(bounds.max().x(), origin.x(), nx);
    const int y0 = index(bounds.min().y(), origin.y(), ny);
    const int y1 = index(bounds.max().y(), origin.y(), ny);
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        const Eigen::Vector2d lo = origin + cell * Eigen::Vector2d(ix, iy) - slack;
        const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(cell) + 2.0 * slack;
        if (!overlaps(Eigen::AlignedBox2d(lo, hi))) continue;
        const auto i = static_cast<std::size_t>(iy * nx + ix);
        lists[i].push_back(ref);
        top_z[i] = std::max(top_z[i], top);
      }
    }
  }
};

void Flatten(const std::vector<std::vector<std::uint32_t>>& lists,
             std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& refs) {
  offsets.assign(1, 0);
  for (const auto& list : lists) {
    refs.insert(refs.end(), list.begin(), list.end());
    offsets.push_back(static_cast<std::uint32_t>(refs.size()));
  }
}

void FileSolids(const CompiledStatics& s, CellLists& cells) {
  for (std::size_t i = 0; i < s.boxes.size(); ++i) {
    const auto corners = FootprintCorners(s.boxes[i]);
    cells.File(MakeRef(RefKind::kBox, i), FootprintBounds(corners), s.boxes[i].z_top(),
               [&](const Eigen::AlignedBox2d& c) { return QuadOverlapsCell(corners, c); });
  }
  for (std::size_t i = 0; i < s.cylinders.size(); ++i) {
    const VerticalCylinder& c = s.cylinders[i];
    cells.File(MakeRef(RefKind::kCylinder, i), FootprintBounds(c), c.z_top,
               [&](const Eigen::AlignedBox2d& b) {
                 return DiskOverlapsCell(c.center, c.radius + kFilingSlack, b);
               });
  }
  for (std::size_t i = 0; i < s.prisms.size(); ++i) {
    const Prism& p = s.prisms[i];
    const Eigen::Vector2d* v = s.prism_vertices.data() + p.first_vertex;
    cells.File(MakeRef(RefKind::kPrism, i), Eigen::AlignedBox2d(p.min_xy, p.max_xy), p.z_top,
               [&](const Eigen::AlignedBox2d& b) { return PolygonOverlapsCell(v, p.vertex_count, b); });
  }
  for (std::size_t i = 0; i < s.foliage.size(); ++i) {
    const VerticalCylinder& c = s.foliage[i].volume;
    cells.File(MakeRef(RefKind::kFoliage, i), FootprintBounds(c), c.z_top,
               [&](const Eigen::AlignedBox2d& b) {
                 return DiskOverlapsCell(c.center, c.radius + kFilingSlack, b);
               });
  }
  for (std::size_t i = 0; i < s.ramps.size(); ++i) {
    const RampSolid& r = s.ramps[i];
    cells.File(MakeRef(RefKind::kRamp, i), FootprintBounds(r.footprint), r.base + r.rise,
               [&](const Eigen::AlignedBox2d& b) { return QuadOverlapsCell(r.footprint, b); });
  }
}

}  // namespace

SceneGrid SceneGrid::Build(const CompiledStatics& statics, const Eigen::AlignedBox2d& bounds,
                           double cell_size_m, std::size_t max_cells) {
  SceneGrid grid;
  if (bounds.isEmpty()) return grid;
  const Eigen::Vector2d size = bounds.sizes() + Eigen::Vector2d::Constant(2.0);  // 1 m margin
  double cell = cell_size_m;
  while ((size.x() / cell + 1.0) * (size.y() / cell + 1.0) > static_cast<double>(max_cells)) {
    cell *= 1.5;
  }
  CellLists cells;
  cells.origin = bounds.min() - Eigen::Vector2d::Constant(1.0);
  cells.cell = cell;
  cells.nx = static_cast<int>(std::ceil(size.x() / cell));
  cells.ny = static_cast<int>(std::ceil(size.y() / cell));
  const auto count = static_cast<std::size_t>(cells.nx) * static_cast<std::size_t>(cells.ny);
  cells.lists.resize(count);
  cells.top_z.assign(count, -kInfinity);
  FileSolids(statics, cells);
  Flatten(cells.lists, grid.offsets_, grid.refs_);
  grid.top_z_ = cells.top_z;

  for (auto& list : cells.lists) list.clear();
  for (std::size_t i = 0; i < statics.lanes.size(); ++i) {
    const LaneSegment& lane = statics.lanes[i];
    cells.File(static_cast<std::uint32_t>(i), FootprintBounds(lane), 0.0,
               [&](const Eigen::AlignedBox2d& b) { return CapsuleOverlapsCell(lane, b); });
  }
  Flatten(cells.lists, grid.lane_offsets_, grid.lane_refs_);

  grid.origin_ = cells.origin;
  grid.cell_ = cell;
  grid.inv_cell_ = 1.0 / cell;
  grid.nx_ = cells.nx;
  grid.ny_ = cells.ny;
  return grid;
}

int SceneGrid::IndexAt(double x, double y) const {
  const double fx = std::floor((x - origin_.x()) * inv_cell_);
  const double fy = std::floor((y - origin_.y()) * inv_cell_);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_)) return -1;
  return static_cast<int>(fy) * nx_ + static_cast<int>(fx);
}

GridCell SceneGrid::CellAt(double x, double y) const {
  const int index = IndexAt(x, y);
  return index < 0 ? GridCell{} : Cell(index);
}

std::span<const std::uint32_t> SceneGrid::LanesAt(double x, double y) const {
  const int index = IndexAt(x, y);
  if (index < 0) return {};
  const auto i = static_cast<std::size_t>(index);
  return std::span<const std::uint32_t>(lane_refs_)
      .subspan(lane_offsets_[i], lane_offsets_[i + 1] - lane_offsets_[i]);
}

}  // namespace flat2d::hal::sim::internal
