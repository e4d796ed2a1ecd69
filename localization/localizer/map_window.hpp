// The part of the prior map the tracking matcher holds: a square around the vehicle, read
// from the map's tiles through the reader's bounded cache into a grid sized once, and moved
// when the vehicle has gone recentre_m from its centre. A city-sized map is thus matched in
// the memory of one window plus the tile cache (issue 8 item 2).
//
// The window's cells are the map's cells (its origin is on the map's cell borders), and a
// cell is structure when the map says slammable. Fill reads each overlapping tile once, row
// block by row block, so a move costs one pass over the window's cells.
#pragma once

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "localization/matching/match_grid.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::localization {

struct MapWindowOptions {
  // Side of the square, metres. It must hold the scan's range plus the widest tracking
  // search around any position up to recentre_m from the centre, 2 (35 + 3 + 10) = 96; a
  // relocalization search of 20 m around its centre gets the inner 2 (35 - 5) of its range.
  double side_m = 100.0;
  double recentre_m = 10.0;
};

Status ValidateOptions(const MapWindowOptions& options);

class MapWindow {
 public:
  // The window's grid is allocated here; the map must have square cells of one resolution.
  static Result<MapWindow> Create(const maps::PriorMapReader& map, const MapWindowOptions& options);

  // Moves the window to `position` (map frame) when it has never been filled or `position`
  // is max_offset_m (default recentre_m) or more from its centre, reading the tiles again.
  // Returns whether it moved (the matcher must then be given the grid again); an error names
  // a damaged tile, and the window is then moved again at the next call.
  Result<bool> Cover(maps::PriorMapReader& map, const Eigen::Vector2d& position);
  Result<bool> Cover(maps::PriorMapReader& map, const Eigen::Vector2d& position, double max_offset_m);
  // Viewpoint mode (thesis 7.3.2): the window holds the viewpoint sub-map whose historic
  // pose is nearest `position` (what the mapping drive saw from there), clipped to the
  // window; it changes when another viewpoint is nearer by switch_margin_m. Returns whether
  // it changed; false without viewpoints (the window stays as it was). An error names a
  // damaged viewpoint.
  Result<bool> CoverWithViewpoint(maps::PriorMapReader& map, const Eigen::Vector2d& position,
                                  double switch_margin_m = 1.0);
  int viewpoint() const { return viewpoint_; }  // -1: the mosaic

  const MatchGrid& grid() const { return grid_; }
  bool filled() const { return filled_; }
  const Eigen::Vector2d& centre() const { return centre_; }
  std::uint64_t moves() const { return moves_; }

 private:
  MapWindow(const MapWindowOptions& options, const GridGeometry& geometry);
  Status Fill(maps::PriorMapReader& map, const Eigen::Vector2d& centre);
  Status FillViewpoint(maps::PriorMapReader& map, int index);

  MapWindowOptions options_;
  MatchGrid grid_;
  bool filled_ = false;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  std::uint64_t moves_ = 0;
  int viewpoint_ = -1;
};

}  // namespace flat2d::localization
