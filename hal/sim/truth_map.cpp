#include "hal/sim/truth_map.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "hal/common/angles.hpp"
#include "hal/sim/scene_compile.hpp"
#include "hal/sim/scene_footprint.hpp"

namespace flat2d::hal::sim {
namespace {

// A grid larger than this (cells) is refused rather than filling memory (2 km x 2 km at 0.1 m).
constexpr double kMaxCells = 4e8;

using OverlapTest = std::function<bool(const Eigen::AlignedBox2d&)>;

class Rasterizer {
 public:
  Rasterizer(const Scene& scene, const TruthMapOptions& options, TruthMap& map)
      : scene_(scene), options_(options), map_(map) {}

  // Calls visit(col, row, cell box) for each cell of the map that `bounds` touches.
  template <typename Visit>
  void ForCells(const Eigen::AlignedBox2d& bounds, Visit&& visit) const {
    const auto index = [&](double v, double o, int n) {
      return std::clamp(static_cast<int>(std::floor((v - o) / map_.resolution_m)), 0, n - 1);
    };
    const int c0 = index(bounds.min().x(), map_.origin.x(), map_.width);
    const int c1 = index(bounds.max().x(), map_.origin.x(), map_.width);
    const int r0 = index(bounds.min().y(), map_.origin.y(), map_.height);
    const int r1 = index(bounds.max().y(), map_.origin.y(), map_.height);
    const Eigen::Vector2d cell = Eigen::Vector2d::Constant(map_.resolution_m);
    for (int row = r0; row <= r1; ++row) {
      for (int col = c0; col <= c1; ++col) {
        const Eigen::Vector2d lo = map_.origin + map_.resolution_m * Eigen::Vector2d(col, row);
        visit(col, row, Eigen::AlignedBox2d(lo, lo + cell));
      }
    }
  }

  void Raise(int col, int row, TruthClass truth_class) {
    TruthClass& cell = map_.cells[static_cast<std::size_t>(row) *
                                      static_cast<std::size_t>(map_.width) +
                                  static_cast<std::size_t>(col)];
    cell = std::max(cell, truth_class);
  }

  // Ground steeper than the hazard slope around a ramp (one cell beyond its footprint).
  void MarkSlopes(const internal::RampSolid& ramp) {
    Eigen::AlignedBox2d bounds = internal::FootprintBounds(ramp.footprint);
    const Eigen::Vector2d grow = Eigen::Vector2d::Constant(2.0 * map_.resolution_m);
    bounds = Eigen::AlignedBox2d(bounds.min() - grow, bounds.max() + grow);
    const double max_tan = std::tan(options_.hazard_slope_deg * kDegToRad);
    ForCells(bounds, [&](int col, int row, const Eigen::AlignedBox2d&) {
      if (GroundTangent(map_.CellCenter(col, row)) > max_tan) Raise(col, row, TruthClass::kHazard);
    });
  }

  // A solid between two absolute heights whose footprint overlaps cells per `overlaps`.
  void MarkSolid(const Eigen::AlignedBox2d& bounds, double z_bottom, double z_top,
                 const OverlapTest& overlaps) {
    ForCells(bounds, [&](int col, int row, const Eigen::AlignedBox2d& cell) {
      if (!overlaps(cell)) return;
      const Eigen::Vector2d c = map_.CellCenter(col, row);
      const double ground = scene_.GroundHeight(c.x(), c.y());
      Raise(col, row, SolidClass(z_bottom - ground, z_top - ground));
    });
  }

 private:
  // tan of the ground's steepest slope at p: the analytic normal's, or a central difference
  // one cell wide, whichever is steeper (a step shows as a steep difference).
  double GroundTangent(const Eigen::Vector2d& p) const {
    const Eigen::Vector3d n = scene_.GroundNormal(p.x(), p.y());
    const double analytic = n.head<2>().norm() / std::max(n.z(), 1e-12);
    const double r = map_.resolution_m;
    const auto h = [&](double dx, double dy) { return scene_.GroundHeight(p.x() + dx, p.y() + dy); };
    const double gx = (h(r, 0.0) - h(-r, 0.0)) / (2.0 * r);
    const double gy = (h(0.0, r) - h(0.0, -r)) / (2.0 * r);
    return std::max(analytic, std::hypot(gx, gy));
  }

  TruthClass SolidClass(double bottom_above_ground, double top_above_ground) const {
    if (top_above_ground <= 0.0 || bottom_above_ground > options_.max_structure_bottom_m) {
      return TruthClass::kFree;  // buried, or above the structure band
    }
    // Vertical extent, not the top: a LiDAR needs returns stacked up a face to call it
    // structure, and a fence's 5 cm bars at 0.45 and 1.2 m give one return a fan each.
    const double extent = top_above_ground - std::max(bottom_above_ground, 0.0);
    return extent >= options_.min_structure_height_m ? TruthClass::kOccupied : TruthClass::kHazard;
  }

  const Scene& scene_;
  const TruthMapOptions& options_;
  TruthMap& map_;
};

Status CheckOptions(const TruthMapOptions& o) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.resolution_m)) return MakeError("truth map: resolution_m must be positive");
  if (!(std::isfinite(o.margin_m) && o.margin_m >= 0.0)) {
    return MakeError("truth map: margin_m must be zero or positive");
  }
  if (!positive(o.min_structure_height_m)) {
    return MakeError("truth map: min_structure_height_m must be positive");
  }
  if (!std::isfinite(o.max_structure_bottom_m)) {
    return MakeError("truth map: max_structure_bottom_m must be finite");
  }
  if (!(o.hazard_slope_deg > 0.0 && o.hazard_slope_deg < 90.0)) {
    return MakeError("truth map: hazard_slope_deg must be in (0, 90)");
  }
  return Status::Ok();
}

void MarkStatics(const internal::CompiledStatics& s, Rasterizer& raster) {
  for (const internal::OrientedBox& box : s.boxes) {
    const auto corners = internal::FootprintCorners(box);
    raster.MarkSolid(internal::FootprintBounds(corners), box.z_bottom(), box.z_top(),
                     [&](const Eigen::AlignedBox2d& c) { return internal::QuadOverlapsCell(corners, c); });
  }
  const auto mark_disk = [&](const internal::VerticalCylinder& cyl) {
    raster.MarkSolid(internal::FootprintBounds(cyl), cyl.z_bottom, cyl.z_top,
                     [&](const Eigen::AlignedBox2d& c) {
                       return internal::DiskOverlapsCell(cyl.center, cyl.radius, c);
                     });
  };
  for (const internal::VerticalCylinder& c : s.cylinders) mark_disk(c);
  for (const internal::FoliageVolume& f : s.foliage) mark_disk(f.volume);
  for (const internal::Prism& p : s.prisms) {
    const Eigen::Vector2d* v = s.prism_vertices.data() + p.first_vertex;
    raster.MarkSolid(Eigen::AlignedBox2d(p.min_xy, p.max_xy), p.z_bottom, p.z_top,
                     [&](const Eigen::AlignedBox2d& c) {
                       return internal::PolygonOverlapsCell(v, p.vertex_count, c);
                     });
  }
}

}  // namespace

std::optional<TruthClass> TruthMap::ClassAt(double x, double y) const {
  const double col = std::floor((x - origin.x()) / resolution_m);
  const double row = std::floor((y - origin.y()) / resolution_m);
  if (!(col >= 0.0 && row >= 0.0 && col < width && row < height)) return std::nullopt;
  return At(static_cast<int>(col), static_cast<int>(row));
}

std::vector<std::uint8_t> TruthMap::GrayImage() const {
  std::vector<std::uint8_t> image(cells.size());
  for (int row = 0; row < height; ++row) {
    const auto top_row = static_cast<std::size_t>(height - 1 - row);
    for (int col = 0; col < width; ++col) {
      image[top_row * static_cast<std::size_t>(width) + static_cast<std::size_t>(col)] =
          TruthGray(At(col, row));
    }
  }
  return image;
}

std::uint8_t TruthGray(TruthClass truth_class) {
  switch (truth_class) {
    case TruthClass::kOccupied:
      return kTruthOccupiedGray;
    case TruthClass::kHazard:
      return kTruthHazardGray;
    case TruthClass::kFree:
      break;
  }
  return kTruthFreeGray;
}

Result<TruthMap> RasterizeTruthMap(const Scene& scene, const TruthMapOptions& options) {
  if (Status ok = CheckOptions(options); !ok) return ok.error();
  const Eigen::AlignedBox2d bounds = scene.bounds();
  if (bounds.isEmpty()) return MakeError("truth map: the scene has nothing to map");
  TruthMap map;
  map.resolution_m = options.resolution_m;
  map.origin = bounds.min() - Eigen::Vector2d::Constant(options.margin_m);
  const Eigen::Vector2d size = bounds.sizes() + Eigen::Vector2d::Constant(2.0 * options.margin_m);
  const double cols = std::ceil(size.x() / options.resolution_m);
  const double rows = std::ceil(size.y() / options.resolution_m);
  if (std::max(cols, 1.0) * std::max(rows, 1.0) > kMaxCells) {
    return MakeError("truth map: " + std::to_string(cols) + " x " + std::to_string(rows) +
                     " cells is too many; use a coarser resolution_m");
  }
  map.width = std::max(static_cast<int>(cols), 1);
  map.height = std::max(static_cast<int>(rows), 1);
  map.cells.assign(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height),
                   TruthClass::kFree);

  const internal::CompiledStatics statics = internal::CompileScene(scene.description());
  Rasterizer raster(scene, options, map);
  for (const internal::RampSolid& ramp : statics.ramps) raster.MarkSlopes(ramp);
  MarkStatics(statics, raster);
  return map;
}

}  // namespace flat2d::hal::sim
