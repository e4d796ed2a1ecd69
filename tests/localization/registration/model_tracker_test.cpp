#include "localization/registration/model_tracker.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/testing/pose_error.hpp"

#include "localization/registration/frame_registration.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::localization::registration {
namespace {

using maps::range3d::PinholeIntrinsics;

// A camera in the office room turning and sliding past the furniture: frame k's pose.
Eigen::Isometry3f CameraAt(int k) {
  Eigen::Matrix3f world_R_optical;
  world_R_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const float t = static_cast<float>(k);
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = Eigen::AngleAxisf(0.02F * t, Eigen::Vector3f::UnitZ()).toRotationMatrix() * world_R_optical *
                  Eigen::AngleAxisf(0.3F, Eigen::Vector3f::UnitY()).toRotationMatrix();
  pose.translation() = Eigen::Vector3f(-1.5F + 0.02F * t, 0.3F - 0.01F * t, 1.4F);
  return pose;
}

SnicpFrame FrameAt(int k, std::mt19937& noise) {
  const auto depth = testing::RenderDepth(testing::OfficeRoom(), PinholeIntrinsics{}, CameraAt(k), 0.002F, noise);
  return MakeSnicpFrame(depth, maps::range3d::RangeFrameOptions{}, SnicpOptions{});
}

TEST(ModelTracker, TracksADriftFreeCameraThroughTheMergedModel) {
  ModelTracker tracker(PinholeIntrinsics{}, ModelTrackerOptions{});
  std::mt19937 noise(7);
  std::printf("noise seed 7\n");
  const Eigen::Isometry3d world_T_first = CameraAt(0).cast<double>();
  Eigen::Isometry3d model_T_camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  std::size_t first_frame_points = 0;
  constexpr int kFrames = 12;
  for (int k = 0; k < kFrames; ++k) {
    const SnicpFrame frame = FrameAt(k, noise);
    const TrackedFrame tracked = tracker.Track(frame, model_T_camera, motion);
    ASSERT_TRUE(tracked.merged) << "frame " << k << ": " << FailureName(tracked.result.failure);
    motion = model_T_camera.inverse() * tracked.model_T_camera;
    model_T_camera = tracked.model_T_camera;
    if (k == 0) first_frame_points = tracker.model().size();
    const testing::PoseError e = testing::PoseErrorOf(model_T_camera, world_T_first.inverse() * CameraAt(k).cast<double>());
    std::printf("frame %d: %.2f mm %.3f deg, model %zu points (%zu merged, %zu replaced)\n", k, 1e3 * e.translation_m,
                e.rotation_deg, tracker.model().size(), tracked.merge.merged, tracked.merge.replaced);
    EXPECT_LT(e.translation_m, 0.001) << "frame " << k;
    EXPECT_LT(e.rotation_deg, 0.02) << "frame " << k;
  }
  // The camera turned 12.6 deg and moved 25 cm: merging keeps about a point per pixel of
  // what was seen, not a frame's worth of points per frame.
  EXPECT_LT(tracker.model().size(), 2 * first_frame_points);
}

// A coarse level that cannot pair enough points (its 80 x 60 view holds fewer than the
// 6000 inliers asked for) is passed over: the full level registers from the same guess.
// The finest level is not: with it too sparse the frame fails.
TEST(ModelTracker, ACoarseLevelTooSparseToPairIsPassedOver) {
  ModelTrackerOptions options;
  options.nicp.min_inliers = 6000;
  ModelTracker tracker(PinholeIntrinsics{}, options);
  std::mt19937 noise(7);
  (void)tracker.Track(FrameAt(0, noise), Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  const TrackedFrame tracked = tracker.Track(FrameAt(1, noise), Eigen::Isometry3d::Identity(),
                                             Eigen::Isometry3d::Identity());
  ASSERT_TRUE(tracked.merged) << FailureName(tracked.result.failure);
  const testing::PoseError e =
      testing::PoseErrorOf(tracked.model_T_camera, (CameraAt(0).inverse() * CameraAt(1)).cast<double>());
  EXPECT_LT(e.translation_m, 0.001);
  EXPECT_LT(e.rotation_deg, 0.02);

  options.nicp.min_inliers = 400000;  // more than the 640 x 480 frame has
  ModelTracker starved(PinholeIntrinsics{}, options);
  (void)starved.Track(FrameAt(0, noise), Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  const TrackedFrame failed = starved.Track(FrameAt(1, noise), Eigen::Isometry3d::Identity(),
                                            Eigen::Isometry3d::Identity());
  EXPECT_FALSE(failed.merged);
  EXPECT_EQ(failed.result.failure, RegistrationFailure::kTooFewCorrespondences);
}

TEST(ModelTracker, AFailedRegistrationLeavesTheModelUntouched) {
  ModelTracker tracker(PinholeIntrinsics{}, ModelTrackerOptions{});
  std::mt19937 noise(7);
  (void)tracker.Track(FrameAt(0, noise), Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  const std::size_t before = tracker.model().size();
  hal::cloud::DepthImage blank;
  blank.width = 640;
  blank.height = 480;
  blank.depth_m.assign(640U * 480U, 0.0F);  // nothing measured
  const SnicpFrame nothing = MakeSnicpFrame(blank, maps::range3d::RangeFrameOptions{}, SnicpOptions{});
  const Eigen::Isometry3d predicted = Eigen::Isometry3d(Eigen::Translation3d(0.1, 0.0, 0.0));
  const TrackedFrame tracked = tracker.Track(nothing, Eigen::Isometry3d::Identity(), predicted);
  EXPECT_FALSE(tracked.result.ok());
  EXPECT_FALSE(tracked.merged);
  EXPECT_TRUE(tracked.model_T_camera.isApprox(predicted));
  EXPECT_EQ(tracker.model().size(), before);
}

// NICP at one level, 10 iterations: four office frames 3 poses apart (steps of 6 cm /
// 3.4 deg) tracked from the identity guess; every frame's result, then the last pose's
// error (empty when a frame was not merged).
std::optional<testing::PoseError> TrackOfficeWithNicp(const ModelTrackerOptions& options,
                                                      std::vector<TrackedFrame>& tracked) {
  ModelTracker tracker(PinholeIntrinsics{}, options);
  std::mt19937 noise(11);
  maps::range3d::RangeFrameOptions frames;
  Eigen::Isometry3d model_T_camera = Eigen::Isometry3d::Identity();
  for (int k = 0; k < 4; ++k) {
    const auto depth = testing::RenderDepth(testing::OfficeRoom(), PinholeIntrinsics{}, CameraAt(3 * k), 0.002F, noise);
    SnicpFrame frame;
    frame.levels.push_back(maps::range3d::FrameFromDepth(depth, frames));
    tracked.push_back(tracker.Track(frame, model_T_camera, Eigen::Isometry3d::Identity()));
    if (!tracked.back().merged) return std::nullopt;
    model_T_camera = tracked.back().model_T_camera;
  }
  return testing::PoseErrorOf(model_T_camera, CameraAt(0).cast<double>().inverse() * CameraAt(9).cast<double>());
}

ModelTrackerOptions NicpOneLevel() {
  ModelTrackerOptions options;
  options.scales = {1};
  options.iterations_per_level = 10;
  return options;
}

TEST(ModelTracker, NicpWithOneLevelTracksToo) {
  std::vector<TrackedFrame> tracked;
  const auto e = TrackOfficeWithNicp(NicpOneLevel(), tracked);
  ASSERT_TRUE(e.has_value()) << "frame " << tracked.size() - 1 << " not merged";
  std::printf("nicp after 3 steps of 6 cm / 3.4 deg: %.2f mm %.3f deg\n", 1e3 * e->translation_m, e->rotation_deg);
  EXPECT_LT(e->translation_m, 0.001);
  EXPECT_LT(e->rotation_deg, 0.02);
}

// The coarse-to-fine radius in the tracker: 5 iterations on the model's normals, the last
// 5 on the frame's and the rendered view's refitted over 0.03 m. It must land as well as
// one radius does, pair the refitted points (the inlier share is of those), and spend 10
// iterations at most.
TEST(ModelTracker, NicpOverAFineRadiusTracksToo) {
  ModelTrackerOptions options = NicpOneLevel();
  options.fine_statistics = maps::range3d::SurfaceStatisticsOptions{};
  options.fine_statistics->radius_m = 0.03F;
  std::vector<TrackedFrame> tracked;
  const auto e = TrackOfficeWithNicp(options, tracked);
  ASSERT_TRUE(e.has_value()) << "frame " << tracked.size() - 1 << " not merged";
  for (std::size_t k = 1; k < tracked.size(); ++k) {
    EXPECT_LE(tracked[k].result.iterations, 10);
    EXPECT_GT(tracked[k].inlier_share, 0.5) << "frame " << k;
  }
  std::printf("nicp over 0.1 then 0.03 m after 3 steps of 6 cm / 3.4 deg: %.2f mm %.3f deg\n",
              1e3 * e->translation_m, e->rotation_deg);
  EXPECT_LT(e->translation_m, 0.001);
  EXPECT_LT(e->rotation_deg, 0.02);
}

// An HDL-32E in the office room, 1080 columns, turning 0.03 rad and moving `step` metres
// along x a revolution: revolution k's pose and range frame.
std::pair<Eigen::Isometry3d, maps::range3d::RangeFrame> OfficeRevolution(int k, float step) {
  maps::range3d::RangeFrameOptions frames;
  frames.lidar_columns = 1080;
  Eigen::Isometry3f world_T_sensor = Eigen::Isometry3f::Identity();
  world_T_sensor.linear() = Eigen::AngleAxisf(0.03F * static_cast<float>(k), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  world_T_sensor.translation() = Eigen::Vector3f(-1.0F + step * static_cast<float>(k), -0.5F, 1.2F);
  return {world_T_sensor.cast<double>(),
          testing::RenderLidarFrame(testing::OfficeRoom(), maps::range3d::SensorModel::kHdl32e, world_T_sensor, frames)};
}

// Tracks revolutions 0..last of OfficeRevolution from the identity guess; the pose error of
// the last against the truth (or nullopt, saying which failed).
std::optional<testing::PoseError> TrackOffice(const ModelTrackerOptions& options, int last, float step) {
  ModelTracker tracker(maps::range3d::LidarProjection(maps::range3d::SensorModel::kHdl32e, 1080), options);
  Eigen::Isometry3d model_T_sensor = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d world_T_first = OfficeRevolution(0, step).first;
  for (int k = 0; k <= last; ++k) {
    auto [world_T_sensor, revolution] = OfficeRevolution(k, step);
    SnicpFrame frame;
    frame.levels.push_back(std::move(revolution));
    const TrackedFrame tracked = tracker.Track(frame, model_T_sensor, Eigen::Isometry3d::Identity());
    if (!tracked.merged) {
      std::printf("revolution %d: %s\n", k, FailureName(tracked.result.failure));
      return std::nullopt;
    }
    model_T_sensor = tracked.model_T_camera;
    if (k == last) return testing::PoseErrorOf(model_T_sensor, world_T_first.inverse() * world_T_sensor);
  }
  return std::nullopt;
}

// A spinning LiDAR in the office room: the model is seen through the sensor's own spherical
// view (no widening) at one level, and drifts less than the same revolutions chained.
TEST(ModelTracker, TracksASpinningLidarThroughItsSphericalView) {
  auto revolution_at = [](int k) { return OfficeRevolution(k, 0.08F); };
  const maps::range3d::RangeProjection lidar =
      maps::range3d::LidarProjection(maps::range3d::SensorModel::kHdl32e, 1080);
  ModelTrackerOptions options;
  options.iterations_per_level = 10;
  options.model.tau_min_m = 0.05F;
  options.model.tau_ratio = 0.01F;
  ModelTracker tracker(lidar, options);
  Eigen::Isometry3d model_T_sensor = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d chained = Eigen::Isometry3d::Identity();  // revolution to revolution
  maps::range3d::RangeFrame previous;
  const Eigen::Isometry3d world_T_first = revolution_at(0).first;
  Eigen::Isometry3d first_T_last;
  for (int k = 0; k < 8; ++k) {
    auto [world_T_sensor, revolution] = revolution_at(k);
    if (k > 0) {
      chained = chained * RegisterFrames(previous, revolution, Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp,
                                         NicpOptions{})
                              .result.target_T_source;
    }
    SnicpFrame frame;
    frame.levels.push_back(revolution);
    const TrackedFrame tracked = tracker.Track(frame, model_T_sensor, Eigen::Isometry3d::Identity());
    ASSERT_TRUE(tracked.merged) << "revolution " << k << ": " << FailureName(tracked.result.failure);
    model_T_sensor = tracked.model_T_camera;
    previous = std::move(revolution);
    first_T_last = world_T_first.inverse() * world_T_sensor;
  }
  const testing::PoseError model = testing::PoseErrorOf(model_T_sensor, first_T_last);
  const testing::PoseError chain = testing::PoseErrorOf(chained, first_T_last);
  std::printf("lidar after 7 steps of 8 cm / 1.7 deg: model %.2f mm %.3f deg (%zu points), chained %.2f mm %.3f deg\n",
              1e3 * model.translation_m, model.rotation_deg, tracker.model().size(), 1e3 * chain.translation_m,
              chain.rotation_deg);
  EXPECT_LT(model.translation_m, 0.006);  // measured 3.6 mm, 0.068 deg; chained 4.2 mm, 0.083 deg
  EXPECT_LT(model.rotation_deg, 0.1);
  EXPECT_LT(model.rotation_deg, chain.rotation_deg);
}

// The pyramid of 6.3.1 for a LiDAR: the revolution and the rendered view at 1/8, 1/4 and 1/2
// of their columns, every row kept, 3 iterations at each.
TEST(ModelTracker, TracksASpinningLidarThroughAPyramidOfColumns) {
  ModelTrackerOptions pyramid;
  pyramid.lidar_column_scales = {8, 4, 2};
  pyramid.iterations_per_level = 3;
  pyramid.model.tau_min_m = 0.05F;
  pyramid.model.tau_ratio = 0.01F;
  const std::optional<testing::PoseError> e = TrackOffice(pyramid, 7, 0.08F);
  ASSERT_TRUE(e.has_value());
  std::printf("lidar pyramid 1/8 1/4 1/2 after 7 steps of 8 cm / 1.7 deg: %.2f mm %.3f deg\n", 1e3 * e->translation_m,
              e->rotation_deg);
  EXPECT_LT(e->translation_m, 0.01);
  EXPECT_LT(e->rotation_deg, 0.15);
}

}  // namespace
}  // namespace flat2d::localization::registration
