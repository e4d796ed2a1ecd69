// The daemon's localization path from raw inputs to global poses, one object for flat2dd
// and flat2d-localize (issue 9 item 5: the offline tool runs this code, not a copy).
//
//   CAN frames --CanOdometry--> dead-reckoned samples in the pose history (local frame)
//   Velodyne datagrams --VelodyneStream--> revolutions --RevolutionGridder--> grids
//     (each fan placed with the history's pose at its time: motion compensation)
//   grid --Localizer--> L2G;  PoseAt(t) = L2G x odometry(t)
//
// Inputs must come in time order across both sources (the daemon receives them so; an
// offline replay merges the two files by timestamp), so that a fan's odometry is known
// when the fan arrives (the history extrapolates the last 50 ms).
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "hal/can/can_frame.hpp"
#include "hal/can/dbc.hpp"
#include "hal/net/udp_datagram.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/localizer/localizer.hpp"
#include "localization/odometry/can_odometry.hpp"
#include "localization/odometry/odometry_config.pb.h"
#include "maps/grid/revolution_gridder.hpp"
#include "maps/grid/structure_grid_options.pb.h"
#include "maps/grid/vehicle_pose_source.hpp"

namespace flat2d::localization {

struct LocalizationPipelineOptions {
  hal::velodyne::VelodyneStreamOptions stream;
  maps::StructureGridOptions grid;
  LocalizerOptions localizer;
  PoseHistoryOptions history;
};

// local_T_vehicle from the pose history, for the gridder's motion compensation.
class HistoryPoseSource : public maps::VehiclePoseSource {
 public:
  explicit HistoryPoseSource(const PoseHistory& history) : history_(history) {}
  std::optional<Eigen::Isometry2d> PoseAt(TimeNs t) const override;

 private:
  const PoseHistory& history_;
};

class LocalizationPipeline {
 public:
  // Called after every complete revolution the localizer took.
  using RevolutionHandler = std::function<void(const maps::PublishedGrid&, const RevolutionReport&)>;

  static Result<std::unique_ptr<LocalizationPipeline>> Create(const hal::can::Dbc& dbc, const OdometryConfig& odometry,
                                                              maps::PriorMapReader map,
                                                              const LocalizationPipelineOptions& options);

  // A CAN frame; returns the dead-reckoning update when it carried odometry (and then
  // advances the localizer's state to the sample's time, Localizer::Tick).
  std::optional<DeadReckoningUpdate> PushCan(const hal::can::CanFrame& frame);
  void PushDatagram(const hal::net::UdpDatagram& datagram);
  // End of input: the stream's last partial revolution is dropped (it is not complete).
  void Finish();

  void set_revolution_handler(RevolutionHandler handler) { on_revolution_ = std::move(handler); }
  Localizer& localizer() { return localizer_; }
  const Localizer& localizer() const { return localizer_; }
  const CanOdometry& odometry() const { return odometry_; }
  const hal::velodyne::VelodyneStream& stream() const { return *stream_; }
  GlobalPose PoseAt(TimeNs time_ns) const { return localizer_.PoseAt(time_ns, odometry_.history()); }
  // Set when the gridder could not be made for the stream's model (the pipeline then idles).
  const std::optional<Error>& failure() const { return failure_; }

 private:
  LocalizationPipeline(CanOdometry odometry, Localizer localizer, const LocalizationPipelineOptions& options);
  void OnRevolution(const hal::velodyne::Revolution& revolution);

  LocalizationPipelineOptions options_;
  CanOdometry odometry_;
  Localizer localizer_;
  HistoryPoseSource poses_;
  std::unique_ptr<hal::velodyne::VelodyneStream> stream_;
  std::optional<maps::RevolutionGridder> gridder_;
  std::optional<Error> failure_;
  RevolutionHandler on_revolution_;
};

}  // namespace flat2d::localization
