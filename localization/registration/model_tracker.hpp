// Frame-to-model tracking of depth frames (thesis 5.1.4, 5.2.2-5.2.3): each new frame is
// registered against the merged model rather than the frame before it, then merged in.
//
//   1. The model is rendered from the last tracked pose, the reference, through a
//      projection wider than the camera's (5.2.2), so that the frame stays inside the
//      reference view while the optimization moves it; coarser levels take every s-th
//      pixel of that view. Rendered from its own pose, a frame's image comes back pixel
//      for pixel, so with a model of one frame this is frame-to-frame registration.
//      A spinning LiDAR's spherical view sees all round already; its coarser levels
//      (6.3.1's pyramid) keep every row (a HDL-32E has 32) and take every s-th column, of
//      the rendered view and of the revolution alike.
//   2. The frame is registered to the rendered view in the inverse form of Eq. 5.20 from
//      the predicted motion: the reference projection is fixed and the frame moves, level
//      by level (NICP: one level, 10 iterations; SNICP: 1/4, 1/2, full, 3 iterations
//      each, 5.3; LiDAR: options.lidar_column_scales). A coarse level too sparse to pair
//      enough points is passed over; the finest level decides.
//   3. On success the frame's full-resolution cloud is merged at the estimated pose
//      (maps/range3d/surfel_model.hpp); a failed registration keeps the prediction and
//      leaves the model untouched, so one bad frame cannot corrupt it. Registration fails
//      by NICP's own tests or when it pairs too small a share of the frame's points.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "localization/registration/nicp_options.hpp"
#include "localization/registration/registration_result.hpp"
#include "localization/registration/snicp.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "maps/range3d/surfel_model.hpp"

namespace flat2d::localization::registration {

struct ModelTrackerOptions {
  NicpOptions nicp;                  // its iterations are replaced by iterations_per_level
  std::vector<int> scales{4, 2, 1};  // the frame's levels, coarse to fine; the last is 1
  // A spherical view's levels, coarse to fine, as divisors of its columns (each must divide
  // them; one that does not ends the pyramid there). The revolution comes as one level and
  // its coarser ones are drawn from it. The thesis' 1/8, 1/4, 1/2 is {8, 4, 2}.
  std::vector<int> lidar_column_scales{1};
  int iterations_per_level = 3;
  // Set: coarse-to-fine statistics radius (frame_registration.hpp, RegisterFramesOverRadii)
  // at the finest level, when that level is the frame's full resolution: its last
  // iterations (IterationsPerRadius) pair normals refitted with these options (its
  // radius_m the fine R), the frame's and the rendered view's. Empty: the model's normals
  // throughout.
  std::optional<maps::range3d::SurfaceStatisticsOptions> fine_statistics;
  // The reference view's extra width and height on each side, as a share of the image's.
  float margin = 0.125F;
  // A registration that pairs fewer than this share of the frame's points with normals is
  // taken as failed (it has slid off the model), so it is not merged.
  float min_inlier_share = 0.3F;
  maps::range3d::SurfelModelOptions model;
};

struct TrackedFrame {
  RegistrationResult result;  // reference_T_camera; iterations summed over the levels
  Eigen::Isometry3d model_T_camera = Eigen::Isometry3d::Identity();
  bool merged = false;
  // The registration's inliers as a share of the frame's points with normals at the finest
  // level (what min_inlier_share is held against; 0 when nothing was registered).
  double inlier_share = 0.0;
  maps::range3d::MergeStats merge;
  double render_ms = 0.0;
  double register_ms = 0.0;
  double merge_ms = 0.0;
};

class ModelTracker {
 public:
  // `intrinsics`: the camera's full-resolution image.
  ModelTracker(const maps::range3d::PinholeIntrinsics& intrinsics, const ModelTrackerOptions& options);
  // `sensor`: the full-resolution projection. A pinhole camera's view is widened by
  // options.margin; a spinning LiDAR's spherical view sees all round already and is
  // registered at options.lidar_column_scales.
  ModelTracker(const maps::range3d::RangeProjection& sensor, const ModelTrackerOptions& options);

  // `frame.levels` matches options.scales (MakeSnicpFrame, or one FrameFromDepth level);
  // a LiDAR revolution is one full-resolution level.
  // The model is seen from model_T_reference (the last tracked pose) and the frame starts
  // at reference_T_guess. The first frame only seeds the model, at model_T_reference *
  // reference_T_guess.
  TrackedFrame Track(const SnicpFrame& frame, const Eigen::Isometry3d& model_T_reference,
                     const Eigen::Isometry3d& reference_T_guess);

  const maps::range3d::SurfelModel& model() const { return model_; }

 private:
  void RenderReference(const Eigen::Isometry3f& model_T_reference);
  // `finest_points`: the points with normals of the last level registered (what
  // min_inlier_share is held against).
  RegistrationResult RegisterLevels(const SnicpFrame& frame, const Eigen::Isometry3d& reference_T_guess,
                                    float& finest_points);
  // The finest level's last iterations on normals refitted with options_.fine_statistics,
  // from `coarse` (that level's result over the first iterations).
  RegistrationResult RefineOverFineRadius(const maps::range3d::RangeFrame& finest, const NicpOptions& nicp,
                                          const RegistrationResult& coarse);
  // The points registered at `level`: the frame's own level for a camera, every s-th
  // column of the revolution for a LiDAR (drawn into level_sources_).
  const maps::range3d::SurfelCloud& SourceAt(const SnicpFrame& frame, std::size_t level);

  const ModelTrackerOptions options_;
  maps::range3d::SurfelModel model_;
  std::vector<int> scales_;                                   // of the levels registered
  maps::range3d::RangeProjection full_view_;                  // the (widened) full-resolution view
  std::vector<maps::range3d::RangeProjection> level_views_;  // ... at each scale
  std::vector<maps::range3d::IndexImage> level_images_;
  std::vector<maps::range3d::SurfelCloud> level_sources_;  // LiDAR: the revolution's columns per level
  maps::range3d::SurfelCloud view_;  // the rendered model, camera frame
  maps::range3d::IndexImage view_image_;
  // The fine radius' refits (buffers kept from frame to frame): the rendered view's and
  // the finest level's points with their statistics from options_.fine_statistics.
  maps::range3d::SurfaceStatistics fine_statistics_;
  maps::range3d::SurfelCloud fine_view_;
  maps::range3d::SurfelCloud fine_source_;
};

}  // namespace flat2d::localization::registration
