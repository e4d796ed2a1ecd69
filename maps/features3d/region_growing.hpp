// Region growing segmentation on the range image, thesis 8.1.4, Algorithm 8: clusters of
// points that belong to one object, grown from a seed whose role moves with the growth.
//
// Pixels are visited row by row; an unlabelled point with a normal starts a cluster and a
// FIFO pool. The point taken from the pool joins the cluster and acts as the seed for its
// own image neighbours (+-1 row, +-neighbour_cols columns, azimuth wrapping round): a
// neighbour joins the pool when it is near (Eq. 8.2: ||p_s - p_i|| < eps_d) and its
// normal agrees (Eq. 8.3: n_s . n_i > eps_n). Algorithm 8 needs both; the text of 8.1.4
// says either is enough: JoinRule picks. A moving seed lets a wall grow end to end where
// a fixed one would cut it every eps_d. Clusters of eps_c points or fewer are dropped, and
// those spanning fewer than min_rows rows (our option).
//
// Sparse LiDAR rows are 1.3-2 deg apart, so eps_d may grow with the seed's range
// (max_distance_per_m); 0 gives the thesis' constant.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "maps/features3d/feature_options.pb.h"
#include "maps/range3d/index_image.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::features3d {

// The points of every kept cluster, cluster after cluster: cluster k is
// points[begin[k] .. begin[k + 1]).
struct Clusters {
  std::vector<std::int32_t> points;
  std::vector<std::size_t> begin{0};

  std::size_t size() const { return begin.size() - 1; }
  std::size_t size_of(std::size_t k) const { return begin[k + 1] - begin[k]; }
};

class RegionGrowing {
 public:
  explicit RegionGrowing(const SegmentationOptions& options)
      : options_(options), min_normal_dot_(static_cast<float>(options.min_normal_dot())),
        either_(options.join() == SegmentationOptions::EITHER) {}

  // Segments the points `image` shows (indices into cloud, whose normals must be computed);
  // points without a normal belong to no cluster. The result lives until the next call.
  const Clusters& Segment(const range3d::IndexImage& image, const range3d::SurfelCloud& cloud);

 private:
  // The point taken from the pool, as its neighbours are judged against it.
  struct Seed {
    Eigen::Vector3f point;
    Eigen::Vector3f normal;
    Eigen::Vector3f line_direction;  // zero unless its neighbourhood is a line
    float max_distance_squared;      // eps_d at its range, squared
  };
  Seed SeedAt(const range3d::SurfelCloud& cloud, std::size_t seed) const;
  bool Joins(const Seed& seed, const range3d::SurfelCloud& cloud, std::size_t candidate) const;
  // Grows the cluster of pixel `start` into clusters_'s tail; returns its size and the rows
  // it spans.
  std::pair<std::size_t, int> Grow(std::size_t start, const range3d::IndexImage& image, const range3d::SurfelCloud& cloud);

  const SegmentationOptions options_;
  const float min_normal_dot_;  // eps_n
  const bool either_;           // the text's rule instead of Algorithm 8's
  Clusters clusters_;
  std::vector<std::uint8_t> labelled_;  // per pixel: in a cluster (kept or dropped) or queued
  std::vector<std::size_t> pool_;       // pixel offsets; at most one entry per pixel
};

}  // namespace flat2d::maps::features3d
