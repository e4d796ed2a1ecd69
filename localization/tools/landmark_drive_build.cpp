#include "localization/tools/landmark_drive_build.hpp"

#include <chrono>

#include "hal/common/time.hpp"
#include "localization/tools/deskewed_drive.hpp"
#include "localization/tools/grid_run.hpp"
#include "maps/features3d/feature_extractor.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::tools {
namespace {

using Clock = std::chrono::steady_clock;

// Revolution by revolution: extract, hand to the graph.
class LandmarkMapper {
 public:
  LandmarkMapper(const LandmarkDriveOptions& options, const Eigen::Isometry3d& vehicle_T_sensor, LandmarkDriveResult& result)
      : options_(options), result_(result), slam_(options.slam, vehicle_T_sensor),
        up_((vehicle_T_sensor.linear().transpose() * Eigen::Vector3d::UnitZ()).cast<float>()) {}

  void Add(const DeskewedRevolution& revolution) {
    const Clock::time_point start = Clock::now();
    const maps::range3d::SensorModel sensor = maps::range3d::SensorModelOf(revolution.model);
    if (!extractor_) {
      extractor_.emplace(maps::features3d::ProjectionForSensor(options_.features, sensor),
                         maps::features3d::OptionsForSensor(options_.features, sensor));
      result_.sensor = std::string(maps::range3d::SensorModelName(sensor));
    }
    const maps::features3d::FeatureSet& features = extractor_->Extract(revolution.cloud.points, up_);
    result_.features_ms.push_back(revolution.deskew_ms + MillisecondsSince(start));
    const Clock::time_point slam_start = Clock::now();
    slam_.Add(revolution.stamp, revolution.world_T_vehicle, features);
    result_.slam_ms.push_back(MillisecondsSince(slam_start));
    result_.odometry.push_back({revolution.stamp, revolution.world_T_vehicle});
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
  const LandmarkDriveOptions& options_;
  LandmarkDriveResult& result_;
  landmarks::LandmarkSlam slam_;
  const Eigen::Vector3f up_;
  std::optional<maps::features3d::FeatureExtractor> extractor_;
};

}  // namespace

Result<LandmarkDriveResult> BuildLandmarkDrive(const LandmarkDriveOptions& options) {
  if (Status valid = maps::ValidateStructureGridOptions(options.grid); !valid.ok()) return valid.error();
  DeskewedDriveOptions walk;
  walk.capture = options.capture;
  walk.can_log = options.can_log;
  walk.dbc = options.dbc;
  walk.odometry_config = options.odometry_config;
  walk.vehicle_T_sensor = maps::VehicleFromSensor(options.grid.mounting());
  walk.stream = options.stream;
  walk.anchor = options.anchor;
  walk.max_revolutions = options.max_revolutions;
  LandmarkDriveResult result;
  LandmarkMapper mapper(options, walk.vehicle_T_sensor, result);
  auto walked = WalkDeskewedDrive(walk, [&](const DeskewedRevolution& revolution) { mapper.Add(revolution); });
  if (!walked.ok()) return walked.error();
  result.revolutions_without_odometry = walked->revolutions_without_odometry;
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
