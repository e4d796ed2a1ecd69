#include "localization/tools/nicp_drive_build.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "hal/cloud/kitti_bin_file.hpp"
#include "hal/cloud/kitti_sequence.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/trajectory/kitti_pose_file.hpp"
#include "localization/registration/model_tracker.hpp"
#include "localization/registration/rigid_transform.hpp"
#include "localization/tools/grid_run.hpp"
#include "localization/tools/odometry_poses.hpp"
#include "localization/tools/revolution_cloud.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/structure_grid_config.hpp"

namespace flat2d::localization::tools {
namespace {

using Clock = std::chrono::steady_clock;

// The revolution-to-revolution tracker: one call per complete revolution, in time order.
class RevolutionTracker {
 public:
  RevolutionTracker(const NicpDriveOptions& options, const maps::InterpolatedPoses* odometry, NicpDriveResult& result)
      : options_(options), odometry_(odometry), result_(result),
        vehicle_T_sensor_(maps::VehicleFromSensor(options.grid.mounting())) {}

  void Add(const hal::velodyne::Revolution& revolution, hal::velodyne::Model model) {
    const TimeNs stamp = revolution.start_ns();
    const Clock::time_point load_start = Clock::now();
    Add(RevolutionCloud(revolution, Deskewing(stamp)), stamp, maps::range3d::SensorModelOf(model), load_start);
  }

  // A KITTI scan, taken as it is stored (KITTI's odometry scans are not deskewed: at 10 Hz
  // and 8 m/s the last points are 0.8 m behind the first).
  void Add(hal::cloud::PointCloud scan, TimeNs stamp, const Clock::time_point& load_start) {
    Add(std::move(scan), stamp, maps::range3d::SensorModel::kKitti64, load_start);
  }

  // Hands the last local map to the caller, if any is open.
  void Finish() {
    if (model_tracker_ && options_.local_map_distance_m > 0.0 && result_.frames > map_first_) {
      CloseLocalMap(result_.frames - 1, false);
    }
  }

 private:
  struct Registration {
    bool ok = false;  // a failure, or a result that is not finite (nothing downstream survives a NaN)
    Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
    double ms = 0.0;  // the registration alone
    double overlap = 1.0;  // against the model: the share of the revolution's points with normals that are inliers
  };

  // One revolution's cloud in the sensor frame at `stamp`, loaded since load_start.
  void Add(hal::cloud::PointCloud cloud, TimeNs stamp, maps::range3d::SensorModel sensor, const Clock::time_point& load_start) {
    if (options_.ground_clearance_m >= 0.0) RemoveGround(cloud);
    const double load_ms = MillisecondsSince(load_start);
    const Clock::time_point frame_start = Clock::now();
    registration::SnicpFrame frame;  // one level: the model tracker's input, kept as it is
    frame.levels.push_back(maps::range3d::FrameFromCloud(cloud, sensor, options_.frames));
    const maps::range3d::RangeFrame& current = frame.levels.front();
    if (result_.frames == 0) {
      Start(stamp);
      world_T_map_ = world_T_sensor_;
      if (options_.frame_to_model) SeedModel(frame);
      StartLocalModel(current);
    } else {
      const Eigen::Isometry3d guess = Guess(stamp);
      const Registration r = options_.frame_to_model ? AgainstModel(frame, guess) : AgainstKeyframe(current, guess);
      result_.frame_ms.push_back(MillisecondsSince(frame_start));
      result_.registration_ms.push_back(r.ms);
      result_.load_ms.push_back(load_ms);
      MoveTo(stamp, r.ok ? r.world_T_sensor : world_T_sensor_ * guess, r.ok);
      if (r.ok && local_model_) MergeIntoLocalModel(current);
      if (CutsLocalMap(r)) StartLocalMap(frame, r.ok);
    }
    Record(stamp, current);
    result_.sensor = std::string(maps::range3d::SensorModelName(current.sensor));
    if (!options_.frame_to_model && (result_.frames == 1 || IsNewKeyframe())) {
      keyframe_ = std::move(frame.levels.front());
      world_T_keyframe_ = world_T_sensor_;
    }
    previous_ns_ = stamp;
  }

  // The revolution registered to the keyframe, from the guess of its motion since the
  // previous revolution.
  Registration AgainstKeyframe(const maps::range3d::RangeFrame& current, const Eigen::Isometry3d& guess) const {
    const Eigen::Isometry3d keyframe_T_previous = world_T_keyframe_.inverse() * world_T_sensor_;
    const registration::FrameRegistration r =
        registration::RegisterFrames(keyframe_, current, keyframe_T_previous * guess, options_.method, options_.nicp);
    return {r.result.ok() && r.result.target_T_source.matrix().allFinite(), world_T_keyframe_ * r.result.target_T_source,
            1e3 * r.seconds};
  }

  // The revolution registered to the model seen from the previous pose, from the guess, and
  // merged into it.
  Registration AgainstModel(const registration::SnicpFrame& frame, const Eigen::Isometry3d& guess) {
    const registration::TrackedFrame tracked = model_tracker_->Track(frame, world_T_sensor_, guess);
    return {tracked.merged && tracked.model_T_camera.matrix().allFinite(), tracked.model_T_camera, tracked.register_ms,
            tracked.inlier_share};
  }

  // Moves world_T_sensor_ to the revolution's pose (the guess's where registration failed).
  void MoveTo(TimeNs stamp, const Eigen::Isometry3d& world_T_current, bool registered) {
    if (!registered) ++result_.failures;
    const Eigen::Isometry3d rigid = registration::Orthonormalized(world_T_current);
    motion_ = world_T_sensor_.inverse() * rigid;
    motion_ns_ = stamp - previous_ns_;
    world_T_sensor_ = options_.planar ? OnThePlane(rigid) : rigid;
  }

  // Whether the revolution just moved to (index result_.frames) ends the current local map,
  // counting the reason: a failed registration, the distance travelled in the map, the
  // rotation from its first revolution, or too small an overlap with the tracked model.
  bool CutsLocalMap(const Registration& r) {
    if (!options_.frame_to_model || options_.local_map_distance_m <= 0.0) return false;
    map_path_m_ += motion_.translation().norm();
    LocalMapCuts& cuts = result_.local_map_cuts;
    const double rotation = Eigen::AngleAxisd((world_T_map_.inverse() * world_T_sensor_).linear()).angle();
    int* reason = nullptr;
    if (!r.ok) reason = &cuts.failure;
    else if (map_path_m_ >= options_.local_map_distance_m) reason = &cuts.distance;
    else if (options_.local_map_angle_rad > 0.0 && rotation >= options_.local_map_angle_rad) reason = &cuts.angle;
    else if (r.overlap < options_.local_map_min_overlap) reason = &cuts.overlap;
    if (reason != nullptr) ++*reason;
    return reason != nullptr;
  }

  // Closes the current map (with the current revolution when it was merged into it) and
  // starts a new one with the current revolution at its pose. The tracker starts afresh
  // too, unless tracking is continuous and the revolution registered.
  void StartLocalMap(const registration::SnicpFrame& frame, bool registered) {
    const int current = result_.frames;
    CloseLocalMap(registered ? current : current - 1, !registered);
    if (!options_.continuous_tracking || !registered) SeedModel(frame);
    StartLocalModel(frame.levels.front());
    map_first_ = current;
    map_path_m_ = 0.0;
    world_T_map_ = world_T_sensor_;
  }

  void CloseLocalMap(int last_revolution, bool ends_in_failure) {
    if (!options_.on_local_map) return;
    const maps::range3d::SurfelCloud& points = local_model_ ? local_model_->cloud() : model_tracker_->model().cloud();
    options_.on_local_map({points, world_T_map_, map_first_, last_revolution, ends_in_failure});
  }

  // With continuous tracking, the local map's own model, seeded with `first`.
  void StartLocalModel(const maps::range3d::RangeFrame& first) {
    if (!options_.continuous_tracking || options_.local_map_distance_m <= 0.0 || !options_.frame_to_model) return;
    local_model_.emplace(options_.model);
    MergeIntoLocalModel(first);
  }

  void MergeIntoLocalModel(const maps::range3d::RangeFrame& frame) {
    (void)local_model_->Merge(frame.cloud, frame.image, frame.projection, world_T_sensor_.cast<float>());
  }

  void SeedModel(const registration::SnicpFrame& first) {
    registration::ModelTrackerOptions tracker;
    tracker.nicp = options_.nicp;
    tracker.nicp.metric = registration::MetricOf(options_.method);
    tracker.lidar_column_scales = options_.lidar_pyramid;
    tracker.iterations_per_level = options_.lidar_pyramid.size() > 1 ? options_.pyramid_iterations : options_.nicp.iterations;
    tracker.model = options_.model;
    tracker.min_inlier_share = options_.min_inlier_share;
    model_tracker_.emplace(first.levels.front().projection, tracker);
    (void)model_tracker_->Track(first, world_T_sensor_, Eigen::Isometry3d::Identity());
  }

  // The sensor where the vehicle would be on the ground plane: height, roll and pitch zero.
  Eigen::Isometry3d OnThePlane(const Eigen::Isometry3d& world_T_sensor) const {
    const Eigen::Isometry3d world_T_vehicle = world_T_sensor * vehicle_T_sensor_.inverse();
    const maps::StampedPose2d flat = maps::Flatten(0, world_T_vehicle);
    const Eigen::Isometry2d planar = Eigen::Translation2d(flat.position) * Eigen::Rotation2Dd(flat.yaw);
    return maps::Lift(planar) * vehicle_T_sensor_;
  }

  // The keyframe is left once the sensor is keyframe_distance_m or keyframe_angle_rad from it.
  bool IsNewKeyframe() const {
    const Eigen::Isometry3d keyframe_T_sensor = world_T_keyframe_.inverse() * world_T_sensor_;
    return keyframe_T_sensor.translation().norm() >= options_.keyframe_distance_m ||
           Eigen::AngleAxisd(keyframe_T_sensor.rotation()).angle() >= options_.keyframe_angle_rad;
  }

 private:
  // The sensor's motion from t0 to t by the odometry (none outside its time).
  std::optional<Eigen::Isometry3d> OdometryMotion(TimeNs t0, TimeNs t) const {
    if (odometry_ == nullptr) return std::nullopt;
    return tools::OdometrySensorMotion(*odometry_, vehicle_T_sensor_, t0, t);
  }

  // The previous motion, scaled to the time from t0 to t.
  Eigen::Isometry3d ConstantVelocity(TimeNs t0, TimeNs t) const {
    if (motion_ns_ <= 0) return Eigen::Isometry3d::Identity();
    return ScaledMotion(motion_, static_cast<double>(t - t0) / static_cast<double>(motion_ns_));
  }

  Eigen::Isometry3d Guess(TimeNs stamp) {
    if (auto odometry = OdometryMotion(previous_ns_, stamp)) return *odometry;
    if (odometry_ != nullptr) ++result_.guesses_without_odometry;
    return ConstantVelocity(previous_ns_, stamp);
  }

  SensorMotion Deskewing(TimeNs reference_ns) const {
    if (!options_.deskew) return {};
    return [this, reference_ns](TimeNs t) {
      if (auto odometry = OdometryMotion(reference_ns, t)) return *odometry;
      return ConstantVelocity(reference_ns, t);
    };
  }

  // Drops the points below the clearance beyond the ground range, taking the ground as the
  // vehicle's plane.
  void RemoveGround(hal::cloud::PointCloud& cloud) const {
    const Eigen::Isometry3f vehicle_T_sensor = vehicle_T_sensor_.cast<float>();
    const auto clearance = static_cast<float>(options_.ground_clearance_m);
    const auto range_squared = static_cast<float>(options_.ground_range_m * options_.ground_range_m);
    std::erase_if(cloud.points, [&](const Eigen::Vector3f& p) {
      return (vehicle_T_sensor * p).z() < clearance && p.head<2>().squaredNorm() > range_squared;
    });
  }

  // The first revolution's pose: the anchor's, else the odometry's, else the origin.
  void Start(TimeNs stamp) {
    const double time_s = static_cast<double>(stamp) * 1e-9;
    Eigen::Isometry3d world_T_vehicle = Eigen::Isometry3d::Identity();
    Se2 anchor;
    if (!options_.anchor.empty() && evaluation::PoseAt(options_.anchor, time_s, 1.0, anchor)) {
      world_T_vehicle = maps::Lift(Eigen::Isometry2d(Eigen::Translation2d(anchor.translation()) * Eigen::Rotation2Dd(anchor.theta())));
    } else if (odometry_ != nullptr) {
      if (auto pose = odometry_->PoseAt(stamp)) world_T_vehicle = maps::Lift(*pose);
    }
    world_T_sensor_ = world_T_vehicle * vehicle_T_sensor_;
    if (odometry_ != nullptr) {
      if (auto pose = odometry_->PoseAt(stamp)) world_T_odometry_ = world_T_vehicle * maps::Lift(*pose).inverse();
    }
  }

  void Record(TimeNs stamp, const maps::range3d::RangeFrame& frame) {
    const Eigen::Isometry3d world_T_vehicle = world_T_sensor_ * vehicle_T_sensor_.inverse();
    result_.trajectory.push_back({stamp, world_T_vehicle});
    if (world_T_odometry_) {
      if (auto pose = odometry_->PoseAt(stamp)) result_.odometry.push_back({stamp, *world_T_odometry_ * maps::Lift(*pose)});
    }
    if (options_.model_every > 0 && result_.frames % options_.model_every == 0) AddToModel(frame.cloud);
    ++result_.frames;
  }

  void AddToModel(const maps::range3d::SurfelCloud& cloud) {
    const Eigen::Isometry3f pose = world_T_sensor_.cast<float>();
    for (std::size_t i = 0; i < cloud.size(); i += static_cast<std::size_t>(options_.model_stride)) {
      if (!cloud.has_normal(i)) continue;
      result_.model_points.push_back(pose * cloud.points[i]);
      result_.model_normals.push_back(pose.linear() * cloud.normals[i]);
    }
  }

  const NicpDriveOptions& options_;
  const maps::InterpolatedPoses* odometry_;
  NicpDriveResult& result_;
  const Eigen::Isometry3d vehicle_T_sensor_;
  Eigen::Isometry3d world_T_sensor_ = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> world_T_odometry_;  // places the odometry at the first pose
  Eigen::Isometry3d motion_ = Eigen::Isometry3d::Identity();  // previous_T_current of the last pair
  TimeNs motion_ns_ = 0;                                       // ... and the time it took
  maps::range3d::RangeFrame keyframe_;  // the revolution the next one registers to
  std::optional<registration::ModelTracker> model_tracker_;  // frame to model instead
  std::optional<maps::range3d::SurfelModel> local_model_;    // continuous tracking's local map
  Eigen::Isometry3d world_T_keyframe_ = Eigen::Isometry3d::Identity();
  TimeNs previous_ns_ = 0;
  // The open local map: its first revolution, frame and the path travelled in it.
  int map_first_ = 0;
  Eigen::Isometry3d world_T_map_ = Eigen::Isometry3d::Identity();
  double map_path_m_ = 0.0;
};

Result<std::optional<maps::InterpolatedPoses>> OpenOdometry(const NicpDriveOptions& options) {
  if (!options.can_log) return std::optional<maps::InterpolatedPoses>();
  auto poses = DeadReckonedPoses(*options.dbc, *options.odometry_config, *options.can_log);
  if (!poses.ok()) return poses.error();
  if (poses->size() < 2) return MakeError(options.can_log->string() + ": fewer than 2 odometry poses");
  return std::optional<maps::InterpolatedPoses>(std::move(*poses));
}

// The capture's complete revolutions through the tracker, then the map gridded at the poses.
Status TrackCapture(const NicpDriveOptions& options, RevolutionTracker& tracker, NicpDriveResult& result) {
  auto source = hal::net::OpenCapture(options.capture);
  if (!source.ok()) return source.error();
  hal::velodyne::VelodyneStream* stream = nullptr;
  auto on_revolution = [&](const hal::velodyne::Revolution& revolution) {
    if (!revolution.complete || (options.max_revolutions > 0 && result.frames >= options.max_revolutions)) return;
    tracker.Add(revolution, stream->identification()->model);
  };
  hal::velodyne::VelodyneStream velodyne(options.stream, on_revolution);
  stream = &velodyne;
  while (auto datagram = (*source)->Next()) velodyne.Push(*datagram);
  velodyne.Finish();
  tracker.Finish();
  if (velodyne.model_error()) return MakeError(options.capture.string() + ": " + velodyne.model_error()->message);
  if (result.frames == 0) return MakeError(options.capture.string() + ": no complete Velodyne revolution");
  if (!options.build_map) return Status::Ok();
  const Clock::time_point grid_start = Clock::now();
  auto mosaic = GridCaptureAtPoses(options.capture, options.grid, options.stream, options.accumulation, result.trajectory);
  if (!mosaic.ok()) return mosaic.error();
  result.mosaic = std::move(*mosaic);
  result.grid_seconds = MillisecondsSince(grid_start) * 1e-3;
  return Status::Ok();
}

// The truth of a KITTI sequence holding poses.txt and calib.txt, as world_T_vehicle at the
// scans' stamps in the tracking's world (the first scan's vehicle frame, the tracking's start
// without an anchor); empty without those files.
Result<std::vector<hal::trajectory::StampedPose>> KittiTruth(const NicpDriveOptions& options,
                                                             const hal::cloud::KittiSequence& sequence) {
  const std::filesystem::path poses_path = options.capture / "poses.txt", calib_path = options.capture / "calib.txt";
  std::vector<hal::trajectory::StampedPose> truth;
  if (!std::filesystem::exists(poses_path) || !std::filesystem::exists(calib_path)) return truth;
  auto cameras = hal::trajectory::ReadKittiPoses(poses_path);
  if (!cameras.ok()) return cameras.error();
  auto cam0_T_velo = hal::trajectory::ReadKittiCalibration(calib_path);
  if (!cam0_T_velo.ok()) return cam0_T_velo.error();
  if (cameras->size() < sequence.scans.size()) {
    return MakeError(poses_path.string() + ": " + std::to_string(cameras->size()) + " poses for " +
                     std::to_string(sequence.scans.size()) + " scans");
  }
  const std::vector<Eigen::Isometry3d> velodyne = hal::trajectory::VelodyneFromKittiCamera(*cameras, *cam0_T_velo);
  const Eigen::Isometry3d vehicle_T_sensor = maps::VehicleFromSensor(options.grid.mounting());
  for (std::size_t i = 0; i < sequence.scans.size(); ++i) {
    truth.push_back({sequence.stamps[i], vehicle_T_sensor * velodyne[i] * vehicle_T_sensor.inverse()});
  }
  return truth;
}

// A KITTI sequence's scans through the tracker, with its truth when it has one. No map: the
// structure grid's gridder works on Velodyne fans (laser table, firing order).
Status TrackKittiSequence(const NicpDriveOptions& options, RevolutionTracker& tracker, NicpDriveResult& result) {
  auto sequence = hal::cloud::OpenKittiSequence(options.capture);
  if (!sequence.ok()) return sequence.error();
  for (std::size_t i = 0; i < sequence->scans.size(); ++i) {
    if (options.max_revolutions > 0 && result.frames >= options.max_revolutions) break;
    const Clock::time_point load_start = Clock::now();
    auto scan = hal::cloud::ReadKittiBin(sequence->scans[i]);
    if (!scan.ok()) return scan.error();
    tracker.Add(std::move(*scan), sequence->stamps[i], load_start);
  }
  tracker.Finish();
  auto truth = KittiTruth(options, *sequence);
  if (!truth.ok()) return truth.error();
  result.truth = std::move(*truth);
  result.truth.resize(static_cast<std::size_t>(result.frames));
  return Status::Ok();
}

}  // namespace

Result<NicpDriveResult> TrackDriveByNicp(const NicpDriveOptions& options) {
  if (options.can_log.has_value() != options.dbc.has_value() || options.dbc.has_value() != options.odometry_config.has_value()) {
    return MakeError("CAN odometry needs a CAN log, a DBC and an odometry configuration together");
  }
  if (Status valid = maps::ValidateStructureGridOptions(options.grid); !valid.ok()) return valid.error();
  auto odometry = OpenOdometry(options);
  if (!odometry.ok()) return odometry.error();
  NicpDriveResult result;
  RevolutionTracker tracker(options, *odometry ? &**odometry : nullptr, result);
  const Status tracked = hal::cloud::IsKittiSequence(options.capture) ? TrackKittiSequence(options, tracker, result)
                                                                       : TrackCapture(options, tracker, result);
  if (!tracked.ok()) return tracked.error();
  return result;
}

}  // namespace flat2d::localization::tools
