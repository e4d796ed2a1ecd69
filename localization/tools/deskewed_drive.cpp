#include "localization/tools/deskewed_drive.hpp"

#include <chrono>
#include <optional>

#include "hal/net/datagram_source.hpp"
#include "localization/tools/odometry_poses.hpp"
#include "localization/tools/revolution_cloud.hpp"
#include "maps/grid/interpolated_poses.hpp"

namespace flat2d::localization::tools {
namespace {

// Revolution by revolution: the odometry's pose, the deskewed cloud, the caller.
class RevolutionWalker {
 public:
  RevolutionWalker(const DeskewedDriveOptions& options, const maps::InterpolatedPoses& odometry,
                   const RevolutionHandler& handle, DeskewedDriveSummary& summary)
      : options_(options), odometry_(odometry), handle_(handle), summary_(summary) {}

  void Add(const hal::velodyne::Revolution& revolution, hal::velodyne::Model model) {
    const TimeNs stamp = revolution.start_ns();
    const std::optional<Eigen::Isometry2d> odometry_pose = odometry_.PoseAt(stamp);
    if (!odometry_pose) {
      ++summary_.revolutions_without_odometry;
      return;
    }
    const Eigen::Isometry3d odometry_T_vehicle = maps::Lift(*odometry_pose);
    if (!world_T_odometry_) Start(stamp, odometry_T_vehicle);
    const auto start = std::chrono::steady_clock::now();
    const hal::cloud::PointCloud cloud = RevolutionCloud(revolution, [&](TimeNs t) {
      return OdometrySensorMotion(odometry_, options_.vehicle_T_sensor, stamp, t).value_or(Eigen::Isometry3d::Identity());
    });
    const double deskew_ms = MillisecondsSince(start);
    ++summary_.revolutions;
    handle_(DeskewedRevolution{stamp, cloud, *world_T_odometry_ * odometry_T_vehicle, model, deskew_ms});
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

  const DeskewedDriveOptions& options_;
  const maps::InterpolatedPoses& odometry_;
  const RevolutionHandler& handle_;
  DeskewedDriveSummary& summary_;
  std::optional<Eigen::Isometry3d> world_T_odometry_;
};

}  // namespace

Result<DeskewedDriveSummary> WalkDeskewedDrive(const DeskewedDriveOptions& options, const RevolutionHandler& handle) {
  auto poses = DeadReckonedPoses(options.dbc, options.odometry_config, options.can_log);
  if (!poses.ok()) return poses.error();
  if (poses->size() < 2) return MakeError(options.can_log.string() + ": fewer than 2 odometry poses");
  const maps::InterpolatedPoses odometry(std::move(*poses));
  auto source = hal::net::OpenCapture(options.capture);
  if (!source.ok()) return source.error();
  DeskewedDriveSummary summary;
  RevolutionWalker walker(options, odometry, handle, summary);
  hal::velodyne::VelodyneStream* stream = nullptr;
  auto on_revolution = [&](const hal::velodyne::Revolution& revolution) {
    if (!revolution.complete || (options.max_revolutions > 0 && summary.complete_revolutions >= options.max_revolutions)) return;
    ++summary.complete_revolutions;
    walker.Add(revolution, stream->identification()->model);
  };
  hal::velodyne::VelodyneStream velodyne(options.stream, on_revolution);
  stream = &velodyne;
  while (auto datagram = (*source)->Next()) velodyne.Push(*datagram);
  velodyne.Finish();
  if (velodyne.model_error()) return MakeError(options.capture.string() + ": " + velodyne.model_error()->message);
  if (summary.complete_revolutions == 0) return MakeError(options.capture.string() + ": no complete Velodyne revolution");
  if (summary.revolutions == 0) {
    return MakeError(options.can_log.string() + ": the CAN odometry covers none of the capture's revolutions");
  }
  return summary;
}

}  // namespace flat2d::localization::tools
