#include "localization/registration/model_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "hal/common/time.hpp"
#include "localization/registration/correspondence_finder.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/registration/nicp.hpp"
#include "localization/registration/rigid_transform.hpp"

namespace flat2d::localization::registration {

namespace {

using Clock = std::chrono::steady_clock;
using maps::range3d::PinholeIntrinsics;
using maps::range3d::RangeProjection;


// The camera's intrinsics with `margin` of extra image on each side, rounded to whole
// pixels of the coarsest level so every level keeps the same principal point.
PinholeIntrinsics Widened(const PinholeIntrinsics& camera, float margin, int coarsest) {
  auto padding = [&](int size) {
    const int pixels = static_cast<int>(std::lround(margin * static_cast<float>(size)));
    return (pixels + coarsest - 1) / coarsest * coarsest;
  };
  const int pad_cols = padding(camera.cols), pad_rows = padding(camera.rows);
  return {camera.cols + 2 * pad_cols, camera.rows + 2 * pad_rows, camera.fx, camera.fy,
          camera.cx + static_cast<float>(pad_cols), camera.cy + static_cast<float>(pad_rows)};
}

// A level's pixel (row, col) is pixel (row s, col s) of the full view (as UnprojectDepth).
PinholeIntrinsics Scaled(const PinholeIntrinsics& full, int scale) {
  const float inverse = 1.0F / static_cast<float>(scale);
  return {full.cols / scale, full.rows / scale, full.fx * inverse, full.fy * inverse, full.cx * inverse,
          full.cy * inverse};
}

// The pairs a registration of `cloud` could make.
float PointsWithNormals(const maps::range3d::SurfelCloud& cloud) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) count += cloud.has_normal(i) ? 1 : 0;
  return static_cast<float>(count);
}

// `out` takes `points` with every normal undefined until fitted (its buffers kept).
void ResetTo(const std::vector<Eigen::Vector3f>& points, maps::range3d::SurfelCloud& out) {
  out.points.assign(points.begin(), points.end());
  out.Resize(points.size());
}

// The points `frame`'s image shows in every scale-th column, into `out` (its buffers kept).
void EveryColumn(const maps::range3d::RangeFrame& frame, int scale, maps::range3d::SurfelCloud& out) {
  out.points.clear();
  out.normals.clear();
  out.curvature.clear();
  out.disc_gain.clear();
  const maps::range3d::SurfelCloud& cloud = frame.cloud;
  for (int row = 0; row < frame.image.rows(); ++row) {
    for (int col = 0; col < frame.image.cols(); col += scale) {
      const std::int32_t index = frame.image.at(row, col);
      if (index < 0) continue;
      const auto i = static_cast<std::size_t>(index);
      out.points.push_back(cloud.points[i]);
      out.normals.push_back(cloud.normals[i]);
      out.curvature.push_back(cloud.curvature[i]);
      out.disc_gain.push_back(cloud.disc_gain[i]);
    }
  }
}

}  // namespace

ModelTracker::ModelTracker(const PinholeIntrinsics& intrinsics, const ModelTrackerOptions& options)
    : ModelTracker(RangeProjection::Pinhole(intrinsics), options) {}

ModelTracker::ModelTracker(const RangeProjection& sensor, const ModelTrackerOptions& options)
    : options_(options), model_(options.model), fine_statistics_(options.fine_statistics.value_or(maps::range3d::SurfaceStatisticsOptions{})) {
  if (!sensor.pinhole()) {
    full_view_ = sensor;
    for (const int scale : options.lidar_column_scales) {
      RangeProjection level = sensor.ColumnsDividedBy(scale);
      if (level.rows() == 0) break;
      scales_.push_back(scale);
      level_views_.push_back(std::move(level));
    }
    if (scales_.empty()) {
      scales_.push_back(1);
      level_views_.push_back(sensor);
    }
    level_sources_.resize(scales_.size());
  } else {
    scales_ = options.scales;
    int coarsest = 1;
    for (const int scale : scales_) coarsest = std::max(coarsest, scale);
    const PinholeIntrinsics wide = Widened(sensor.intrinsics(), options.margin, coarsest);
    full_view_ = RangeProjection::Pinhole(wide);
    for (const int scale : scales_) level_views_.push_back(RangeProjection::Pinhole(Scaled(wide, scale)));
  }
  view_image_.Reserve(full_view_.rows(), full_view_.cols());
  for (const RangeProjection& view : level_views_) level_images_.emplace_back().Reserve(view.rows(), view.cols());
}

TrackedFrame ModelTracker::Track(const SnicpFrame& frame, const Eigen::Isometry3d& model_T_reference,
                                 const Eigen::Isometry3d& reference_T_guess) {
  TrackedFrame tracked;
  tracked.model_T_camera = Orthonormalized(model_T_reference * reference_T_guess);
  if (model_.size() > 0) {
    Clock::time_point start = Clock::now();
    RenderReference(model_T_reference.cast<float>());
    tracked.render_ms = MillisecondsSince(start);
    start = Clock::now();
    float points = 0.0F;
    tracked.result = RegisterLevels(frame, reference_T_guess, points);
    tracked.register_ms = MillisecondsSince(start);
    tracked.inlier_share = points > 0.0F ? tracked.result.inliers / static_cast<double>(points) : 0.0;
    if (tracked.result.ok() && tracked.result.inliers < options_.min_inlier_share * points) {
      tracked.result.failure = RegistrationFailure::kTooFewCorrespondences;
    }
    if (!tracked.result.ok()) return tracked;
    tracked.model_T_camera = Orthonormalized(model_T_reference * tracked.result.target_T_source);
  }
  const Clock::time_point start = Clock::now();
  const maps::range3d::RangeFrame& full = frame.levels.back();
  tracked.merge = model_.Merge(full.cloud, full.image, full.projection, tracked.model_T_camera.cast<float>());
  tracked.merged = true;
  tracked.merge_ms = MillisecondsSince(start);
  return tracked;
}

void ModelTracker::RenderReference(const Eigen::Isometry3f& model_T_reference) {
  model_.Render(full_view_, model_T_reference, view_, view_image_);
  for (std::size_t level = 0; level < scales_.size(); ++level) {
    const int scale = scales_[level];
    const int row_step = full_view_.pinhole() ? scale : 1;  // a LiDAR's levels keep every row
    maps::range3d::IndexImage& image = level_images_[level];
    image.Clear(image.rows(), image.cols());
    for (int row = 0; row < image.rows(); ++row) {
      for (int col = 0; col < image.cols(); ++col) {
        const int full_row = row * row_step, full_col = col * scale;
        const std::int32_t index = view_image_.at(full_row, full_col);
        if (index >= 0) image.Set(row, col, index, view_image_.depth(full_row, full_col));
      }
    }
  }
}

RegistrationResult ModelTracker::RegisterLevels(const SnicpFrame& frame, const Eigen::Isometry3d& reference_T_guess,
                                                float& finest_points) {
  NicpOptions nicp = options_.nicp;
  RegistrationResult result;
  result.target_T_source = reference_T_guess;
  int iterations = 0;
  const maps::range3d::SurfelCloud* registered = nullptr;  // the last level's source
  const std::size_t levels = full_view_.pinhole() ? std::min(level_views_.size(), frame.levels.size()) : level_views_.size();
  const std::vector<int> split = IterationsPerRadius(options_.iterations_per_level, 2);  // coarse, fine
  for (std::size_t level = 0; level < levels; ++level) {
    const bool finest = level + 1 == levels;
    const bool refine = finest && options_.fine_statistics && scales_[level] == 1 && split.back() > 0;
    const maps::range3d::RangeFrame& level_frame = full_view_.pinhole() ? frame.levels[level] : frame.levels.back();
    nicp.normal_weight = NormalWeightAt(options_.nicp, level_frame.statistics_radius_m);
    nicp.iterations = refine ? split.front() : options_.iterations_per_level;
    ProjectiveCorrespondenceFinder finder(view_, level_views_[level], &level_images_[level]);
    registered = &SourceAt(frame, level);
    const Eigen::Isometry3d level_guess = result.target_T_source;
    result = Nicp(nicp).Register(view_, finder, *registered, level_guess);
    iterations += result.iterations;
    if (PassOverSparseLevel(finest, level_guess, result)) continue;  // a 40 x 30 view, say
    if (!result.ok()) break;
    if (refine) {
      nicp.iterations = split.back();
      result = RefineOverFineRadius(level_frame, nicp, result);
      iterations += result.iterations;
      registered = &fine_source_;
    }
  }
  finest_points = registered != nullptr ? PointsWithNormals(*registered) : 0.0F;
  result.iterations = iterations;
  return result;
}

RegistrationResult ModelTracker::RefineOverFineRadius(const maps::range3d::RangeFrame& finest, const NicpOptions& nicp,
                                                      const RegistrationResult& coarse) {
  ResetTo(view_.points, fine_view_);
  fine_statistics_.Compute(full_view_, view_image_, fine_view_);
  ResetTo(finest.cloud.points, fine_source_);
  fine_statistics_.Compute(finest.projection, finest.image, fine_source_);
  NicpOptions fine = nicp;
  fine.normal_weight = NormalWeightAt(options_.nicp, options_.fine_statistics->radius_m);
  ProjectiveCorrespondenceFinder finder(fine_view_, level_views_.back(), &level_images_.back());
  return Nicp(fine).Register(fine_view_, finder, fine_source_, coarse.target_T_source);
}

const maps::range3d::SurfelCloud& ModelTracker::SourceAt(const SnicpFrame& frame, std::size_t level) {
  if (full_view_.pinhole()) return frame.levels[level].cloud;
  const maps::range3d::RangeFrame& revolution = frame.levels.back();
  if (scales_[level] == 1) return revolution.cloud;
  EveryColumn(revolution, scales_[level], level_sources_[level]);
  return level_sources_[level];
}

}  // namespace flat2d::localization::registration
