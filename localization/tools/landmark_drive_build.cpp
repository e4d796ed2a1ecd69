#include "localization/tools/landmark_drive_build.hpp"

#include <chrono>

#include "hal/common/time.hpp"
#include "hal/net/datagram_source.hpp"
#include "localization/tools/grid_run.hpp"
#include "localization/tools/odometry_poses.hpp"
#include "localization/tools/revolution_cloud.hpp"
#include "maps/features3d/feature_extractor.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::tools {
namespace {

using Clock = std::chrono::steady_clock;

// Revolution by revolution: deskew, extract, hand to the graph.
class LandmarkMapper {
 public:
  LandmarkMapper(const LandmarkDriveOptions& options, const maps::InterpolatedPoses& odometry, LandmarkDriveResult& result)
      : options_(options), odometry_(odometry), result_(result),
        vehicle_T_sensor_(maps::VehicleFromSensor(options.grid.mounting())), slam_(options.slam, vehicle_T_sensor_),
        up_((vehicle_T_sensor_.linear().transpose() * Eigen::Vector3d::UnitZ()).cast<float>()) {}

  void Add(const hal::velodyne::Revolution& revolution, hal::velodyne::Model model) {
    const TimeNs stamp = revolution.start_ns();
    const auto odometry_pose = odometry_.PoseAt(stamp);
    if (!odometry_pose) {
      ++result_.revolutions_without_odometry;
      return;
    }
    if (!world_T_odometry_) Start(stamp, maps::Lift(*odometry_pose));
    const Clock::time_point start = Clock::now();
    const hal::cloud::PointCloud cloud = RevolutionCloud(revolution, [&](TimeNs t) {
      return OdometrySensorMotion(odometry_, vehicle_T_sensor_, stamp, t).value_or(Eigen::Isometry3d::Identity());
    });
    const maps::range3d::SensorModel sensor = maps::range3d::SensorModelOf(model);
    if (!extractor_) {
      extractor_.emplace(maps::range3d::LidarProjection(sensor, static_cast<int>(options_.features.columns())),
                         options_.features);
      result_.sensor = std::string(maps::range3d::SensorModelName(sensor));
    }
    const maps::features3d::FeatureSet& features = extractor_->Extract(cloud.points, up_);
    result_.features_ms.push_back(MillisecondsSince(start));
    const Eigen::Isometry3d world_T_vehicle = *world_T_odometry_ * maps::Lift(*odometry_pose);
    const Clock::time_point slam_start = Clock::now();
    slam_.Add(stamp, world_T_vehicle, features);
    result_.slam_ms.push_back(MillisecondsSince(slam_start));
    result_.odometry.push_back({stamp, world_T_vehicle});
    ++result_.revolutions;
  }

  void Finish() {
    const Clock::time_point start = Clock::now();
    slam_.Finish();
    result_.finish_ms = MillisecondsSince(start);
    result_.trajectory = slam_.Trajectory();
    result_.planes = slam_.Planes();
    result_.lines = slam_.Lines();
    result_.stats = slam_.stats();
  }

 private:
  // The odometry placed so that its first pose is the anchor's (else where it is).
  void Start(TimeNs stamp, const Eigen::Isometry3d& odometry_T_vehicle) {
    Se2 anchor;
    Eigen::Isometry3d world_T_vehicle = odometry_T_vehicle;
    if (!options_.anchor.empty() && evaluation::PoseAt(options_.anchor, static_cast<double>(stamp) * 1e-9, 1.0, anchor)) {
      world_T_vehicle = maps::Lift(Eigen::Isometry2d(Eigen::Translation2d(anchor.translation()) * Eigen::Rotation2Dd(anchor.theta())));
    }
    world_T_odometry_ = world_T_vehicle * odometry_T_vehicle.inverse();
  }

  const LandmarkDriveOptions& options_;
  const maps::InterpolatedPoses& odometry_;
  LandmarkDriveResult& result_;
  const Eigen::Isometry3d vehicle_T_sensor_;
  landmarks::LandmarkSlam slam_;
  const Eigen::Vector3f up_;
  std::optional<maps::features3d::FeatureExtractor> extractor_;
  std::optional<Eigen::Isometry3d> world_T_odometry_;
};

}  // namespace

Result<LandmarkDriveResult> BuildLandmarkDrive(const LandmarkDriveOptions& options) {
  if (Status valid = maps::ValidateStructureGridOptions(options.grid); !valid.ok()) return valid.error();
  auto poses = DeadReckonedPoses(options.dbc, options.odometry_config, options.can_log);
  if (!poses.ok()) return poses.error();
  if (poses->size() < 2) return MakeError(options.can_log.string() + ": fewer than 2 odometry poses");
  const maps::InterpolatedPoses odometry(std::move(*poses));
  auto source = hal::net::OpenCapture(options.capture);
  if (!source.ok()) return source.error();
  LandmarkDriveResult result;
  LandmarkMapper mapper(options, odometry, result);
  hal::velodyne::VelodyneStream* stream = nullptr;
  int complete = 0;
  auto on_revolution = [&](const hal::velodyne::Revolution& revolution) {
    if (!revolution.complete || (options.max_revolutions > 0 && complete >= options.max_revolutions)) return;
    ++complete;
    mapper.Add(revolution, stream->identification()->model);
  };
  hal::velodyne::VelodyneStream velodyne(options.stream, on_revolution);
  stream = &velodyne;
  while (auto datagram = (*source)->Next()) velodyne.Push(*datagram);
  velodyne.Finish();
  if (velodyne.model_error()) return MakeError(options.capture.string() + ": " + velodyne.model_error()->message);
  if (complete == 0) return MakeError(options.capture.string() + ": no complete Velodyne revolution");
  if (result.revolutions == 0) {
    return MakeError(options.can_log.string() + ": the CAN odometry covers none of the capture's revolutions");
  }
  mapper.Finish();
  if (!options.build_map) return result;
  const Clock::time_point grid_start = Clock::now();
  auto mosaic = GridCaptureAtPoses(options.capture, options.grid, options.stream, options.accumulation, result.trajectory);
  if (!mosaic.ok()) return mosaic.error();
  result.mosaic = std::move(*mosaic);
  result.grid_seconds = MillisecondsSince(grid_start) * 1e-3;
  return result;
}

}  // namespace flat2d::localization::tools
