// The world's true 2D structure, for judging structure grids and prior maps (issue 5,
// item 5), in the classes of the slope-based multi-class detector (thesis 7.1.3, 7.3.1).
//
// occupied: static structure a LiDAR would call slammable: the footprint of every box,
//   wall, building, cylinder, bar and foliage volume that stands at least
//   `min_structure_height_m` tall above the local ground (its vertical extent there) and
//   whose bottom is within the structure band (no higher than `max_structure_bottom_m`
//   above the local ground).
// hazard: obstacles to navigation that are not slammable: solids less tall than that (curbs,
//   low boxes, thesis Fig. 7.6's 0.1 m box; a fence's thin bars, which hold one return per
//   fan at most) and ground steeper than `hazard_slope_deg`
//   (15 deg as in thesis 7.1.3; a 16 deg ramp is hazard, 10 and 14.5 deg ramps are free),
//   which includes the steps at a ramp's sides and drop-off.
// free: everything else. Moving objects are not part of the truth.
//
// Steps: size the grid to the scene's bounds plus a margin; mark ground hazards around each
// ramp from the ground's slope at each cell centre (the analytic normal, and central
// differences of the height one cell apart, which turn a step into a steep slope); then
// rasterize each solid's footprint conservatively (a cell touched by the footprint counts,
// so edges are exact to one cell and a bar thinner than a cell still shows), keeping the
// strongest class per cell (occupied > hazard > free).
//
// Files follow the ROS map_server convention: truth_map.pgm (binary P5, 8 bit, first row
// = largest y) with occupied 0, hazard 128, free 254, and truth_map.yaml (image,
// resolution, origin of the lower-left pixel corner, negate 0, thresholds 0.65 / 0.196,
// mode trinary). map_server reads hazard (128, p = 0.498) as unknown.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "hal/sim/scene.hpp"

namespace flat2d::hal::sim {

enum class TruthClass : std::uint8_t { kFree = 0, kHazard = 1, kOccupied = 2 };

inline constexpr std::uint8_t kTruthOccupiedGray = 0;
inline constexpr std::uint8_t kTruthHazardGray = 128;
inline constexpr std::uint8_t kTruthFreeGray = 254;

struct TruthMapOptions {
  double resolution_m = 0.05;
  double margin_m = 2.0;                // added around the scene's bounds
  double min_structure_height_m = 0.3;  // top above local ground for slammable structure
  double max_structure_bottom_m = 2.0;  // top of the structure band (thesis 7.1.2: 0.2-2 m)
  double hazard_slope_deg = 15.0;       // steeper ground is hazard (thesis 7.1.3)
};

struct TruthMap {
  double resolution_m = 0.05;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // world XY of cell (0, 0)'s lower-left corner
  int width = 0;                                     // columns, along x
  int height = 0;                                    // rows, along y
  std::vector<TruthClass> cells;                     // row-major, row 0 = smallest y

  TruthClass At(int col, int row) const {
    return cells[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(col)];
  }
  Eigen::Vector2d CellCenter(int col, int row) const {
    return origin + resolution_m * Eigen::Vector2d(col + 0.5, row + 0.5);
  }
  // The class of the cell holding (x, y); nullopt outside the map.
  std::optional<TruthClass> ClassAt(double x, double y) const;
  // The image as map_server sees it: width * height gray bytes, top row (largest y) first;
  // what the PGM holds and what a PNG renderer draws.
  std::vector<std::uint8_t> GrayImage() const;
};

std::uint8_t TruthGray(TruthClass truth_class);

Result<TruthMap> RasterizeTruthMap(const Scene& scene, const TruthMapOptions& options = {});

// Writes <dir>/truth_map.pgm and <dir>/truth_map.yaml when `directory_or_stem` is an
// existing directory, else <stem>.pgm and <stem>.yaml.
Status WriteTruthMap(const TruthMap& map, const std::filesystem::path& directory_or_stem);

}  // namespace flat2d::hal::sim
