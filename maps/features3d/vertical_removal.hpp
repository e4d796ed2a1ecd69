// Non-vertical region removal, thesis 8.1.2, Algorithm 7: the points of a spherical depth
// image that do not stack up along gravity (the ground, car roofs, low clutter) are taken
// out before normals and segmentation, which halves the work (Fig. 8.7) and removes the
// surfaces that make no line or plane landmark.
//
// A column of the image holds the lasers of one azimuth, so the points of a vertical
// structure share a column and, projected onto the ground plane, one spot. Per column, top
// row first: a point not yet labelled vertical counts the points of the rows below whose
// ground projections lie within eps_r of its own; more than eps_t and they all are labelled
// vertical, otherwise the point is removed (index -1, depth +inf). O(rows^2) per column.
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
  // The column's valid rows, their points' ground projections and their labels; sized to
  // the image's rows once.
  struct ColumnPoint {
    int row;
    Eigen::Vector3f ground;
  };
  std::size_t ApplyToColumn(int col, range3d::IndexImage& image);

  const VerticalRemovalOptions options_;
  std::vector<ColumnPoint> column_;
  std::vector<std::uint8_t> vertical_;
  std::vector<std::size_t> stack_;  // the rows of the current point's stack
};

}  // namespace flat2d::maps::features3d
