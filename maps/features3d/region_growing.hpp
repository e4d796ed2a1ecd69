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
//
// Thin poles (our addition, pole_max_width_m): a far tree trunk turns its normal by d * da / r
// from one column to the next (16 deg for a 0.2 m trunk 19 m from an HDL-32E), more than
// eps_n lets through, so Eq. 8.3 cuts it into strips of 2-3 columns, each too small or too
// flat to fit. Before the size filter, touching pieces (neighbours by the same image rule
// and Eq. 8.2) whose joint footprint on the ground stays within pole_max_width_m are joined
// again: only something as thin as a pole can be, so walls and cars, whose pieces are wider,
// keep Algorithm 8's cut.
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
  // points without a normal belong to no cluster. `up` (unit, against gravity, sensor
  // frame) sets the ground on which a pole's footprint is measured. The result lives until
  // the next call.
  const Clusters& Segment(const range3d::IndexImage& image, const range3d::SurfelCloud& cloud,
                          const Eigen::Vector3f& up = Eigen::Vector3f::UnitZ());

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
  // A piece grown by Algorithm 8, before the thin ones are joined: its points are
  // piece_points_[begin .. begin + size). For a root of the union-find, joined, rows and
  // footprint are those of everything joined to it.
  struct Piece {
    std::size_t begin = 0, size = 0;
    std::size_t joined = 0;                    // points of the pieces joined to it, its own too
    int top = 0, bottom = 0;                   // rows spanned
    Eigen::Vector2f ground_min, ground_max;    // footprint box on the ground
  };
  // Grows the piece of pixel `start` (Algorithm 8) into piece_points_'s tail.
  void Grow(std::size_t start, const range3d::IndexImage& image, const range3d::SurfelCloud& cloud);
  void JoinThinPieces(const range3d::IndexImage& image, const range3d::SurfelCloud& cloud);
  void JoinIfThin(std::size_t offset, std::size_t neighbour, const range3d::IndexImage& image,
                  const range3d::SurfelCloud& cloud);
  std::int32_t Root(std::int32_t piece);
  // Copies the pieces of each root that passes eps_c and min_rows into clusters_.
  void CollectClusters();
  bool Kept(const Piece& root) const;  // eps_c and min_rows

  const SegmentationOptions options_;
  const float min_normal_dot_;  // eps_n
  const bool either_;           // the text's rule instead of Algorithm 8's
  Clusters clusters_;
  std::vector<std::int32_t> piece_of_;      // per pixel: its piece, or -1 (none, not queued)
  std::vector<std::size_t> pool_;           // pixel offsets; at most one entry per pixel
  std::vector<std::int32_t> piece_points_;  // point indices, piece after piece
  std::vector<Piece> pieces_;
  std::vector<std::int32_t> parent_;        // union-find over pieces
  std::vector<std::size_t> cursor_;         // per kept root: where its next point goes in clusters_
  Eigen::Vector3f ground_x_ = Eigen::Vector3f::UnitX(), ground_y_ = Eigen::Vector3f::UnitY();
};

}  // namespace flat2d::maps::features3d
