#include "maps/features3d/feature_extractor.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "hal/common/time.hpp"
#include "maps/features3d/feature_fit.hpp"
#include "maps/features3d/feature_options.hpp"

namespace flat2d::maps::features3d {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

FeatureExtractor::FeatureExtractor(const range3d::RangeProjection& projection, const FeatureExtractionOptions& options)
    : projection_(projection), options_(options), vertical_(options.vertical()),
      statistics_(StatisticsOptions(options.normals())), segmentation_(options.segmentation()) {
  image_.Reserve(projection.rows(), projection.cols());
}

const FeatureSet& FeatureExtractor::Extract(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& up) {
  stats_ = {};
  stats_.input_points = points.size();
  Clock::time_point start = Clock::now();
  image_.Build(projection_, points, {}, Eigen::Isometry3f::Identity());
  stats_.image_points = DropFarPixels();
  stats_.image_ms = MillisecondsSince(start);

  start = Clock::now();
  stats_.vertical_points = options_.vertical().enabled() ? vertical_.Apply(points, up, image_) : stats_.image_points;
  stats_.vertical_ms = MillisecondsSince(start);

  start = Clock::now();
  cloud_.points.assign(points.begin(), points.end());
  cloud_.Resize(points.size());
  statistics_.Compute(projection_, image_, cloud_);
  KeepSteepLineDirections(up);
  stats_.normals_ms = MillisecondsSince(start);

  start = Clock::now();
  clusters_ = &segmentation_.Segment(image_, cloud_, up);
  stats_.clusters = clusters_->size();
  stats_.segmentation_ms = MillisecondsSince(start);

  start = Clock::now();
  FitClusters(up);
  stats_.fitting_ms = MillisecondsSince(start);
  return features_;
}

// Empties the pixels beyond max_range_m; returns the pixels left.
std::size_t FeatureExtractor::DropFarPixels() {
  const auto max_range = static_cast<float>(options_.max_range_m());
  std::size_t left = 0;
  for (int row = 0; row < image_.rows(); ++row) {
    for (int col = 0; col < image_.cols(); ++col) {
      if (image_.at(row, col) < 0) continue;
      if (max_range > 0.0F && image_.depth(row, col) > max_range) {
        image_.Set(row, col, -1, std::numeric_limits<float>::infinity());
      } else {
        ++left;
      }
    }
  }
  return left;
}

// A neighbourhood along a ring (a wall seen where its rows are sparse) is a line too, but
// by sampling, not by shape: only lines within 45 deg of vertical are the thin poles whose
// direction region growing may compare (the removal has left vertical structure only).
void FeatureExtractor::KeepSteepLineDirections(const Eigen::Vector3f& up) {
  constexpr float kMinSteepness = 0.70710678F;  // cos 45 deg
  for (Eigen::Vector3f& direction : cloud_.line_directions) {
    if (std::abs(direction.dot(up)) < kMinSteepness) direction.setZero();
  }
}

void FeatureExtractor::FitClusters(const Eigen::Vector3f& up) {
  features_.planes.clear();
  features_.lines.clear();
  for (std::size_t k = 0; k < clusters_->size(); ++k) {
    const std::span<const std::int32_t> members(clusters_->points.data() + clusters_->begin[k], clusters_->size_of(k));
    const Feature feature = FitFeature(cloud_.points, members, options_.fitting(), up);
    if (const auto* line = std::get_if<LineFeature>(&feature)) features_.lines.push_back(*line);
    if (const auto* plane = std::get_if<PlaneFeature>(&feature)) features_.planes.push_back(*plane);
  }
}

}  // namespace flat2d::maps::features3d
