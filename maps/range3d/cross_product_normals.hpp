// Fast normals of a range image (thesis 5.2.1, Eq. 5.19), SNICP's replacement for the
// eigen-decomposition of 5.1.1: the cross product of the differences of the points
// `delta` pixels left/right and up/down, then a block filter (the mean of the unit normals
// in a (2 block + 1)^2 window, renormalized).
//
// The block mean's length says how well the normals agree: 1 on a plane, less across a
// crease or on noise. 1 - |mean| stands in for the curvature sigma (Eq. 5.7 compares it
// between two clouds computed the same way), and below the flatness cut the information
// is the disc of Eq. 5.2 / 5.14. Neighbours across a depth jump (the interval image) give
// no normal.
#pragma once

#include <vector>

#include "maps/range3d/index_image.hpp"
#include "maps/range3d/interval_image.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::range3d {

struct CrossProductNormalOptions {
  int delta = 2;                  // Delta of Eq. 5.19: 2-5 pixels
  int block = 2;                  // the block filter's half size
  int min_block_normals = 6;      // fewer raw normals in the block: undefined
  float depth_jump_ratio = 0.1F;  // the interval image's cut
  float flat_curvature = 0.02F;   // 1 - |mean| below this: a disc
  float disc_epsilon = 1e-3F;     // eps of Eq. 5.2
};

class CrossProductNormals {
 public:
  explicit CrossProductNormals(const CrossProductNormalOptions& options) : options_(options) {}

  // Fills cloud's normals, curvature and information for the points `image` indexes.
  void Compute(const IndexImage& image, SurfelCloud& cloud);

 private:
  void RawNormalRow(const IndexImage& image, const SurfelCloud& cloud, int row);
  void RowSums(const IndexImage& image, const SurfelCloud& cloud);
  void BlockFilter(const IndexImage& image, SurfelCloud& cloud);

  const CrossProductNormalOptions options_;
  IntervalImage intervals_;
  std::vector<Eigen::Vector3f> raw_row_;  // one row's raw normals; zero where undefined
  std::vector<Eigen::Vector4f> row_sums_;  // per row, prefix sums of (n, defined): rows x (cols + 1)
};

}  // namespace flat2d::maps::range3d
