#include "localization/localizer/localization_pipeline.hpp"

#include <utility>

#include "hal/velodyne/laser_table.hpp"

namespace flat2d::localization {

std::optional<Eigen::Isometry2d> HistoryPoseSource::PoseAt(TimeNs t) const {
  const PoseAtTime pose = history_.At(t);
  if (!pose.ok()) return std::nullopt;
  Eigen::Isometry2d local_T_vehicle = Eigen::Isometry2d::Identity();
  local_T_vehicle.translate(pose.local_T_vehicle.translation());
  local_T_vehicle.rotate(pose.local_T_vehicle.theta());
  return local_T_vehicle;
}

Result<std::unique_ptr<LocalizationPipeline>> LocalizationPipeline::Create(const hal::can::Dbc& dbc,
                                                                           const OdometryConfig& odometry,
                                                                           maps::PriorMapReader map,
                                                                           const LocalizationPipelineOptions& options) {
  auto can = CanOdometry::Create(dbc, odometry, options.history);
  if (!can.ok()) return can.error();
  auto localizer = Localizer::Create(std::move(map), options.localizer);
  if (!localizer.ok()) return localizer.error();
  return std::unique_ptr<LocalizationPipeline>(
      new LocalizationPipeline(std::move(*can), std::move(*localizer), options));
}

LocalizationPipeline::LocalizationPipeline(CanOdometry odometry, Localizer localizer,
                                           const LocalizationPipelineOptions& options)
    : options_(options),
      odometry_(std::move(odometry)),
      localizer_(std::move(localizer)),
      poses_(odometry_.history()),
      stream_(std::make_unique<hal::velodyne::VelodyneStream>(
          options.stream, [this](const hal::velodyne::Revolution& revolution) { OnRevolution(revolution); })) {}

std::optional<DeadReckoningUpdate> LocalizationPipeline::PushCan(const hal::can::CanFrame& frame) {
  std::optional<DeadReckoningUpdate> update = odometry_.Push(frame);
  // The state follows the clock between revolutions too: a silent LiDAR degrades the fix.
  if (update && update->new_sample()) localizer_.Tick(update->sample.time_ns, odometry_.history());
  return update;
}

void LocalizationPipeline::PushDatagram(const hal::net::UdpDatagram& datagram) { stream_->Push(datagram); }

void LocalizationPipeline::Finish() { stream_->Finish(); }

void LocalizationPipeline::OnRevolution(const hal::velodyne::Revolution& revolution) {
  if (failure_) return;
  // The laser table is known once the stream has identified the model, by its first revolution.
  if (!gridder_) {
    const hal::velodyne::LaserTable table = options_.stream.calibration
                                                ? *options_.stream.calibration
                                                : hal::velodyne::DefaultLaserTable(stream_->identification()->model);
    auto created = maps::RevolutionGridder::Create(table, options_.grid, &poses_,
                                                   options_.stream.revolution.cut_azimuth_rad);
    if (!created.ok()) {
      failure_ = created.error();
      return;
    }
    gridder_.emplace(std::move(*created));
  }
  const maps::PublishedGrid* grid = gridder_->Add(revolution.fans);
  if (grid == nullptr || !grid->complete) return;
  const RevolutionReport report = localizer_.AddGrid(*grid, odometry_.history());
  if (on_revolution_) on_revolution_(*grid, report);
}

}  // namespace flat2d::localization
