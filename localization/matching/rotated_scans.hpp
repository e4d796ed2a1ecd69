// The scan rotated once per searched heading and cut to map cells (Olson 2009, section
// IV-A: rotation is the expensive part, so it is done once per heading, and every
// translation of the search is then an integer offset added to each point's cell).
//
// For heading h the scan is placed at the predicted position with heading
// theta_pred + HeadingOffset(h) and each point's cell is stored; the candidate with
// translation offset (dx, dy) cells, at pose (t_pred + resolution * (dx, dy), theta_h), has
// its points exactly in those cells shifted by (dx, dy). Storage: max_headings x max_points.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "localization/matching/match_grid.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

struct CellOffset {
  std::int32_t x = 0;
  std::int32_t y = 0;
};

// The headings a search visits: 2 * half_count + 1 headings `step` apart around the
// prediction, or, when they would reach around the circle, `count` headings evenly
// covering it.
struct HeadingSet {
  int count = 0;
  double step = 0.0;
  int center = 0;  // index of the predicted heading
  double Offset(int index) const { return (index - center) * step; }
};

// Olson's rule: the step that moves the farthest point by at most one cell,
// acos(1 - r^2 / (2 d^2)); a window of half-width `half_angle` (>= pi: all headings) is
// covered with it. At most max_headings headings: the step grows when it would need more.
HeadingSet ChooseHeadings(double resolution, double max_range, double half_angle,
                          double fixed_step, int max_headings);

class RotatedScans {
 public:
  RotatedScans(int max_headings, std::size_t max_points);

  // Rotates and discretizes `points` (vehicle frame) for every heading of `headings`
  // around `prediction` (map_T_vehicle) on a grid of `geometry`.
  void Prepare(std::span<const Eigen::Vector2d> points, const Se2& prediction,
               const HeadingSet& headings, const GridGeometry& geometry);

  std::span<const CellOffset> Heading(int index) const {
    return {offsets_.data() + static_cast<std::size_t>(index) * max_points_, points_};
  }
  int headings() const { return headings_; }
  std::size_t points() const { return points_; }

 private:
  std::size_t max_points_ = 0;
  int max_headings_ = 0;
  int headings_ = 0;
  std::size_t points_ = 0;
  std::vector<CellOffset> offsets_;  // max_headings x max_points
};

}  // namespace flat2d::localization
