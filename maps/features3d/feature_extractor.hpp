// 3D line and plane features from one sparse LiDAR revolution, thesis 8.1 (Fig. 8.1):
//
//   1. the spherical depth image and its index image (8.1.2; rows = lasers by elevation,
//      columns = azimuth), points beyond max_range_m left out;
//   2. non-vertical region removal (Algorithm 7, vertical_removal.hpp);
//   3. normals by integral images over the interval image (8.1.3, maps/range3d's
//      SurfaceStatistics), only for the points left; where a neighbourhood is a steep line
//      (a thin pole) also its direction, which segmentation compares instead of normals;
//   4. region growing segmentation (Algorithm 8, region_growing.hpp);
//   5. a line, else a plane, fitted to each cluster (Eq. 8.4-8.6, feature_fit.hpp).
//
// The extractor owns every buffer and sizes them by the image (rows x cols) and the largest
// revolution seen, so after the first revolution of a capture it reuses its memory.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "maps/features3d/feature_options.pb.h"
#include "maps/features3d/line_plane_features.hpp"
#include "maps/features3d/region_growing.hpp"
#include "maps/features3d/vertical_removal.hpp"
#include "maps/range3d/index_image.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::features3d {

struct ExtractionStats {
  std::size_t input_points = 0;
  std::size_t image_points = 0;     // pixels showing a point within max_range_m
  std::size_t vertical_points = 0;  // left by the removal (= image_points without it)
  std::size_t clusters = 0;
  // Milliseconds per stage (Fig. 8.7) and in all.
  double image_ms = 0.0, vertical_ms = 0.0, normals_ms = 0.0, segmentation_ms = 0.0, fitting_ms = 0.0;
  double total_ms() const { return image_ms + vertical_ms + normals_ms + segmentation_ms + fitting_ms; }
};

class FeatureExtractor {
 public:
  // `options` must be valid (ValidateFeatureOptions); `projection` the sensor's spherical one.
  FeatureExtractor(const range3d::RangeProjection& projection, const FeatureExtractionOptions& options);

  // The features of `points` (sensor frame, metres); `up` is the unit vector against
  // gravity in the sensor frame (from the mounting). Results live until the next call.
  const FeatureSet& Extract(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& up);

  const ExtractionStats& stats() const { return stats_; }
  // After Extract: the image of the points that went into segmentation, the cloud with
  // their normals and the clusters (for pictures and tests).
  const range3d::IndexImage& image() const { return image_; }
  const range3d::SurfelCloud& cloud() const { return cloud_; }
  const Clusters& clusters() const { return *clusters_; }

 private:
  std::size_t DropFarPixels();
  void KeepSteepLineDirections(const Eigen::Vector3f& up);
  void FitClusters(const Eigen::Vector3f& up);

  const range3d::RangeProjection projection_;
  const FeatureExtractionOptions options_;
  range3d::IndexImage image_;
  VerticalRemoval vertical_;
  range3d::SurfaceStatistics statistics_;
  RegionGrowing segmentation_;
  range3d::SurfelCloud cloud_;
  const Clusters* clusters_ = nullptr;
  FeatureSet features_;
  ExtractionStats stats_;
};

}  // namespace flat2d::maps::features3d
