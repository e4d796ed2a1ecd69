#include "localization/tools/odometry_poses.hpp"

#include <utility>

#include "hal/can/dbc.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/odometry/odometry_config.hpp"

namespace flat2d::localization {

Result<CanLogOdometry> OpenCanLogOdometry(const std::filesystem::path& dbc_path,
                                          const std::filesystem::path& config_path,
                                          const std::filesystem::path& log_path) {
  Result<hal::can::Dbc> dbc = hal::can::LoadDbc(dbc_path);
  if (!dbc.ok()) return dbc.error();
  Result<OdometryConfig> config = LoadOdometryConfig(config_path);
  if (!config.ok()) return config.error();
  Result<CanOdometry> odometry = CanOdometry::Create(*dbc, *config);
  if (!odometry.ok()) return odometry.error();
  Result<hal::can::CandumpReader> reader = hal::can::CandumpReader::Open(log_path);
  if (!reader.ok()) return reader.error();
  return CanLogOdometry{std::move(*odometry), std::move(*reader)};
}

Result<std::vector<maps::StampedPose2d>> DeadReckonedPoses(const std::filesystem::path& dbc_path,
                                                           const std::filesystem::path& config_path,
                                                           const std::filesystem::path& log_path) {
  Result<CanLogOdometry> opened = OpenCanLogOdometry(dbc_path, config_path, log_path);
  if (!opened.ok()) return opened.error();
  std::vector<maps::StampedPose2d> poses;
  hal::can::CanFrame frame;
  while (opened->reader.Next(frame)) {
    const auto update = opened->odometry.Push(frame);
    if (!update || !update->new_sample()) continue;
    const OdometrySample& sample = update->sample;
    poses.push_back({sample.time_ns, sample.local_T_vehicle.translation(), sample.local_T_vehicle.theta()});
  }
  if (poses.size() < 2) {
    return Error{log_path.string() + ": fewer than two odometry samples (does the DBC and "
                 "odometry configuration fit this vehicle?)"};
  }
  return poses;
}

Result<std::vector<maps::StampedPose2d>> TumPoses(const std::filesystem::path& tum) {
  auto trajectory = hal::trajectory::ReadTum(tum);
  if (!trajectory.ok()) return trajectory.error();
  if (trajectory->size() < 2) return Error{tum.string() + ": fewer than two poses"};
  std::vector<maps::StampedPose2d> poses;
  poses.reserve(trajectory->size());
  for (const hal::trajectory::StampedPose& pose : *trajectory) {
    poses.push_back(maps::Flatten(pose.time_ns, pose.world_T_body));
  }
  return poses;
}

}  // namespace flat2d::localization
