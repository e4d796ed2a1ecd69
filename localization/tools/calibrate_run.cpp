#include "localization/tools/calibrate_run.hpp"

#include <algorithm>
#include <chrono>

#include "hal/common/angles.hpp"
#include "hal/trajectory/pose_interpolation.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/tools/deskewed_drive.hpp"
#include "localization/tools/odometry_poses.hpp"
#include "maps/grid/interpolated_poses.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::tools {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// One drive tracked with a mounting, kept with the mounting it used.
struct TrackedDrive {
  NicpDriveResult result;
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();

  // world_T_sensor at tracked revolution i.
  Eigen::Isometry3d Sensor(std::size_t i) const { return result.trajectory[i].world_T_body * vehicle_T_sensor; }
};

Result<TrackedDrive> Track(const CalibrateOptions& options, const CalibrationDrive& drive, const Eigen::Isometry3d& mounting) {
  NicpDriveOptions tracking = options.tracking;
  tracking.capture = drive.capture;
  tracking.can_log = drive.can_log;
  tracking.dbc = drive.dbc;
  tracking.odometry_config = options.odometry_config;
  *tracking.grid.mutable_mounting() = maps::MountingOf(mounting);
  tracking.planar = false;
  tracking.build_map = false;
  tracking.anchor.clear();
  auto tracked = TrackDriveByNicp(tracking);
  if (!tracked.ok()) return tracked.error();
  return TrackedDrive{std::move(*tracked), mounting};
}

// The sensor's and the vehicle's motions over the same intervals: the tracked revolutions
// against the CAN odometry at their stamps (those outside its time left out).
std::vector<calibration::MotionPair> MotionPairsOf(const CalibrateOptions& options, const maps::InterpolatedPoses& vehicle_poses,
                                                   const TrackedDrive& tracked) {
  std::vector<Eigen::Isometry3d> sensor, vehicle;
  for (std::size_t i = 0; i < tracked.result.trajectory.size(); ++i) {
    const auto pose = vehicle_poses.PoseAt(tracked.result.trajectory[i].time_ns);
    if (!pose) continue;
    sensor.push_back(tracked.Sensor(i));
    vehicle.push_back(maps::Lift(*pose));
  }
  return calibration::MotionPairs(sensor, vehicle, options.pair_distance_m, options.pair_angle_rad);
}

// The drive's revolutions deskewed with `mounting` (0 revolutions: all).
DeskewedDriveOptions WalkOf(const CalibrateOptions& options, const CalibrationDrive& drive, const Eigen::Isometry3d& mounting,
                            int revolutions) {
  DeskewedDriveOptions walk;
  walk.capture = drive.capture;
  walk.can_log = drive.can_log;
  walk.dbc = drive.dbc;
  walk.odometry_config = options.odometry_config;
  walk.vehicle_T_sensor = mounting;
  walk.stream = options.tracking.stream;
  walk.max_revolutions = revolutions;
  return walk;
}

double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

// The ground plane in every ground_every-th revolution, deskewed with the guessed mounting.
Result<GroundEstimate> EstimateGround(const CalibrateOptions& options, const CalibrationDrive& drive, const Eigen::Isometry3d& guess) {
  const DeskewedDriveOptions walk = WalkOf(options, drive, guess, options.tracking.max_revolutions);
  const Eigen::Vector3d up = guess.linear().transpose() * Eigen::Vector3d::UnitZ();
  std::vector<double> roll, pitch, height;
  GroundEstimate ground;
  int index = 0;
  auto walked = WalkDeskewedDrive(walk, [&](const DeskewedRevolution& revolution) {
    if (index++ % std::max(options.ground_every, 1) != 0) return;
    ++ground.tried;
    const auto plane = calibration::FitGroundPlane(revolution.cloud.points, up, guess.translation().z(), options.ground);
    if (!plane) return;
    const Eigen::Vector2d roll_pitch = calibration::RollPitchOf(plane->normal);
    roll.push_back(roll_pitch.x());
    pitch.push_back(roll_pitch.y());
    height.push_back(plane->height_m);
  });
  if (!walked.ok()) return walked.error();
  if (height.empty()) return MakeError(drive.capture.string() + ": no ground plane found under the sensor (is the mounting's guess upright?)");
  ground.roll_deg = Median(roll) * kRadToDeg;
  ground.pitch_deg = Median(pitch) * kRadToDeg;
  ground.height_m = Median(height);
  ground.revolutions = static_cast<int>(height.size());
  return ground;
}

// The guess with the ground's roll, pitch and height.
Eigen::Isometry3d WithGround(const Eigen::Isometry3d& guess, const GroundEstimate& ground) {
  maps::SensorMounting mounting = maps::MountingOf(guess);
  mounting.set_roll_deg(ground.roll_deg);
  mounting.set_pitch_deg(ground.pitch_deg);
  mounting.set_z_m(ground.height_m);
  return maps::VehicleFromSensor(mounting);
}

// Sensor to vehicle, the tracking run again with each pass's estimate.
Result<SensorCalibration> CalibrateSensor(const CalibrateOptions& options, const CalibrationDrive& drive, TrackedDrive& last) {
  const Clock::time_point start = Clock::now();
  SensorCalibration calibration;
  Eigen::Isometry3d mounting = drive.initial_vehicle_T_sensor;
  calibration::HandEyeOptions hand_eye = options.hand_eye;
  if (options.use_ground) {
    auto ground = EstimateGround(options, drive, mounting);
    if (!ground.ok()) return ground.error();
    calibration.ground = *ground;
    mounting = WithGround(mounting, *ground);
    hand_eye.fixed = {false, false, true, true, true, false};
  }
  // Dead-reckoned once: only the tracking changes from pass to pass.
  auto odometry = DeadReckonedPoses(drive.dbc, options.odometry_config, drive.can_log);
  if (!odometry.ok()) return odometry.error();
  const maps::InterpolatedPoses vehicle_poses(std::move(*odometry));
  for (int pass = 0; pass < std::max(options.passes, 1); ++pass) {
    auto tracked = Track(options, drive, mounting);
    if (!tracked.ok()) return tracked.error();
    std::vector<calibration::MotionPair> pairs = MotionPairsOf(options, vehicle_poses, *tracked);
    if (options.scale_odometry) {
      calibration.odometry_scale = calibration::OdometryDistanceScale(pairs);
      for (calibration::MotionPair& pair : pairs) pair.vehicle_motion.translation() *= calibration.odometry_scale;
    }
    auto solved = calibration::SolveHandEye(pairs, mounting, hand_eye);
    if (!solved.ok()) return MakeError(drive.capture.string() + ": " + solved.error().message);
    calibration.hand_eye = *solved;
    calibration.sensor = tracked->result.sensor;
    calibration.frames = tracked->result.frames;
    calibration.failures = tracked->result.failures;
    mounting = solved->vehicle_T_sensor;
    last = std::move(*tracked);
  }
  calibration.seconds = SecondsSince(start);
  return calibration;
}

// world_T_sensor at time t along a tracked drive (linear in position, slerp in rotation).
std::optional<Eigen::Isometry3d> SensorAt(const TrackedDrive& drive, TimeNs t) {
  const auto& trajectory = drive.result.trajectory;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    if (trajectory[i].time_ns < t) continue;
    const TimeNs t0 = trajectory[i - 1].time_ns, t1 = trajectory[i].time_ns;
    if (t < t0) return std::nullopt;
    const double s = t1 > t0 ? static_cast<double>(t - t0) / static_cast<double>(t1 - t0) : 0.0;
    return hal::trajectory::InterpolatePose(drive.Sensor(i - 1), drive.Sensor(i), s);
  }
  return std::nullopt;
}

// The drive's first revolutions, ground and all (the tracker cuts the ground it would
// otherwise register, and the ground holds the pair's height, roll and pitch), deskewed with
// the estimated mounting and placed at their tracked poses in the frame of the sensor at the
// first revolution.
Result<maps::range3d::RangeFrame> Reconstruction(const CalibrateOptions& options, const CalibrationDrive& drive, const TrackedDrive& tracked) {
  const DeskewedDriveOptions walk = WalkOf(options, drive, tracked.vehicle_T_sensor, std::max(options.reconstruction_revolutions, 1));
  const Eigen::Isometry3d first_T_world = tracked.Sensor(0).inverse();
  const auto& trajectory = tracked.result.trajectory;
  hal::cloud::PointCloud cloud;
  std::size_t next = 0;  // both walk the capture in time order
  auto walked = WalkDeskewedDrive(walk, [&](const DeskewedRevolution& revolution) {
    while (next < trajectory.size() && trajectory[next].time_ns < revolution.stamp) ++next;
    if (next >= trajectory.size() || trajectory[next].time_ns != revolution.stamp) return;
    const Eigen::Isometry3f first_T_sensor = (first_T_world * tracked.Sensor(next)).cast<float>();
    for (std::size_t i = 0; i < revolution.cloud.points.size(); i += static_cast<std::size_t>(std::max(options.reconstruction_stride, 1))) {
      cloud.points.push_back(first_T_sensor * revolution.cloud.points[i]);
    }
  });
  if (!walked.ok()) return walked.error();
  const std::size_t max_points = static_cast<std::size_t>(std::max(options.reconstruction_max_points, 1));
  if (cloud.points.size() > max_points) {
    const std::size_t keep_every = (cloud.points.size() + max_points - 1) / max_points;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < cloud.points.size(); i += keep_every) cloud.points[kept++] = cloud.points[i];
    cloud.points.resize(kept);
  }
  maps::range3d::RangeFrameOptions frames;
  frames.unorganized_statistics.radius_m = options.reconstruction_radius_m;
  return maps::range3d::FrameFromCloud(cloud, maps::range3d::SensorModel::kUnorganized, frames);
}

Result<SensorPairCalibration> CalibratePair(const CalibrateOptions& options, const TrackedDrive& first, const TrackedDrive& second,
                                            const Eigen::Isometry3d& mounting1, const Eigen::Isometry3d& mounting2) {
  const CalibrationDrive& drive1 = options.drives[0];
  const CalibrationDrive& drive2 = options.drives[1];
  const Clock::time_point start = Clock::now();
  // The first sensor at the second drive's first revolution, from its own first one
  // (the identity when they start together).
  const auto bridge_world = SensorAt(first, second.result.trajectory.front().time_ns);
  if (!bridge_world) {
    return MakeError("calibrate: the second drive's first revolution is outside the first drive's time: not one drive");
  }
  const Eigen::Isometry3d bridge = first.Sensor(0).inverse() * *bridge_world;
  auto target_frame = Reconstruction(options, drive1, first);
  if (!target_frame.ok()) return target_frame.error();
  auto source_frame = Reconstruction(options, drive2, second);
  if (!source_frame.ok()) return source_frame.error();
  const maps::range3d::RangeFrame& target = *target_frame;
  const maps::range3d::RangeFrame& source = *source_frame;
  SensorPairCalibration pair;
  pair.from_hand_eye = mounting1.inverse() * mounting2;
  pair.points1 = target.cloud.size();
  pair.points2 = source.cloud.size();
  // Coarse, then fine: the guess can be as far off as the mountings' guesses where the drive
  // did not constrain them (0.2 m and 5 deg: 1.7 m at 20 m), beyond NICP's 0.5 m gate.
  registration::NicpOptions coarse = options.tracking.nicp;
  coarse.max_distance_m = 2.0F;
  coarse.min_normal_dot = 0.95F;
  const registration::FrameRegistration first_pass = registration::RegisterFrames(
      target, source, bridge * pair.from_hand_eye, options.tracking.method, coarse, registration::CorrespondenceMode::kKdTree);
  const Eigen::Isometry3d guess = first_pass.result.ok() ? first_pass.result.target_T_source : bridge * pair.from_hand_eye;
  const registration::FrameRegistration r = registration::RegisterFrames(target, source, guess, options.tracking.method,
                                                                         options.tracking.nicp, registration::CorrespondenceMode::kKdTree);
  if (!r.result.ok()) {
    return MakeError(std::string("calibrate: the reconstructions did not register (") + registration::FailureName(r.result.failure) + ")");
  }
  pair.sensor1_T_sensor2 = bridge.inverse() * r.result.target_T_source;
  pair.inliers = r.result.inliers;
  pair.iterations = first_pass.result.iterations + r.result.iterations;
  pair.chi2 = r.result.chi2;
  pair.seconds = SecondsSince(start);
  return pair;
}

}  // namespace

Result<CalibrateResult> Calibrate(const CalibrateOptions& options) {
  if (options.drives.empty() || options.drives.size() > 2) return MakeError("calibrate: one or two drives");
  CalibrateResult result;
  std::vector<TrackedDrive> tracked(options.drives.size());
  for (std::size_t d = 0; d < options.drives.size(); ++d) {
    auto sensor = CalibrateSensor(options, options.drives[d], tracked[d]);
    if (!sensor.ok()) return sensor.error();
    result.sensors.push_back(std::move(*sensor));
  }
  if (options.drives.size() == 2) {
    auto pair = CalibratePair(options, tracked[0], tracked[1], result.sensors[0].hand_eye.vehicle_T_sensor,
                              result.sensors[1].hand_eye.vehicle_T_sensor);
    if (!pair.ok()) return pair.error();
    result.pair = *pair;
  }
  return result;
}

}  // namespace flat2d::localization::tools
