// Non-vertical region removal, thesis 8.1.2, Algorithm 7: the points of a spherical depth
// image that do not stack up along gravity (the ground, car roofs, low clutter) are taken
// out before normals and segmentation, which halves the work (Fig. 8.7) and removes the
// surfaces that make no line or plane landmark.
//
// A column of the image holds the lasers of one azimuth (of one firing sequence, with the
// columns by firing of range_frame.hpp's LidarProjection), so the points of a vertical
// structure share a column and, projected onto the ground plane, one spot. Per column, top
// row first: a point not yet labelled vertical counts the points of the rows below whose
// ground projections lie within eps_r of its own; more than eps_t and they all are labelled
// vertical, otherwise the point is removed (index -1, depth +inf). O(rows^2) per column,
// so the ground projections are kept as 2D coordinates in the ground plane, one array per
// axis, and the count runs as a branch-free loop the compiler vectorizes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "maps/features3d/feature_options.pb.h"
#include "maps/range3d/index_image.hpp"

namespace flat2d::maps::features3d {

class VerticalRemoval {
 public:
  explicit VerticalRemoval(const VerticalRemovalOptions& options) : options_(options) {}

  // Removes the non-vertical pixels of `image`, whose indices point into `points` (sensor
  // frame); `up` is gravity's opposite in the sensor frame, unit. Returns the pixels kept.
  std::size_t Apply(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& up, range3d::IndexImage& image);

 private:
  std::size_t ApplyToColumn(int col, range3d::IndexImage& image);
  // How many of the column's points after v lie within eps_r of v on the ground.
  std::size_t CountBelow(std::size_t v, float radius_squared) const;

  const VerticalRemovalOptions options_;
  // The column's valid rows, their points' ground projections (coordinates along two axes
  // orthogonal to `up`) and their labels; each sized to the image's rows once.
  std::vector<int> rows_;
  std::vector<float> ground_x_, ground_y_;
  std::vector<std::uint8_t> vertical_;
};

}  // namespace flat2d::maps::features3d
