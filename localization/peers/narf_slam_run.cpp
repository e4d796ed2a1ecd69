#include "localization/peers/narf_slam_run.hpp"

#include <chrono>

#include "hal/common/time.hpp"
#include "localization/peers/span_timer.hpp"

namespace flat2d::localization::peers {

Result<NarfSlamResult> RunNarfSlam(const NarfSlamOptions& options) {
  using Clock = std::chrono::steady_clock;
  NarfSlamResult result;
  landmarks::LandmarkSlam slam(options.slam, options.drive.vehicle_T_sensor);
  const maps::features3d::FeatureSet no_features;
  auto walked = tools::WalkDeskewedDrive(options.drive, [&](const tools::DeskewedRevolution& revolution) {
    const SpanTimer timer;
    const NarfKeypoints keypoints = DetectNarfKeypoints(revolution.cloud, options.narf);
    result.keypoints_ms.push_back(timer.WallMs());
    result.keypoints_cpu_ms.push_back(timer.CpuMs());
    if (result.revolutions == 0) {
      result.image_width = keypoints.image_width;
      result.image_height = keypoints.image_height;
    }
    const Clock::time_point slam_start = Clock::now();
    slam.Add(revolution.stamp, revolution.world_T_vehicle, no_features, keypoints.points);
    result.slam_ms.push_back(MillisecondsSince(slam_start));
    result.keypoints.push_back(static_cast<int>(keypoints.points.size()));
    result.deskew_ms.push_back(revolution.deskew_ms);
    result.odometry.push_back({revolution.stamp, revolution.world_T_vehicle});
    ++result.revolutions;
  });
  if (!walked.ok()) return walked.error();
  result.revolutions_without_odometry = walked->revolutions_without_odometry;
  const Clock::time_point finish_start = Clock::now();
  slam.Finish();
  result.finish_ms = MillisecondsSince(finish_start);
  result.trajectory = slam.Trajectory();
  result.points = slam.Points();
  result.stats = slam.stats();
  return result;
}

}  // namespace flat2d::localization::peers
