#include "daemon/service/api_handler.hpp"

#include <cmath>

#include "hal/common/time.hpp"

namespace flat2d::daemon {
namespace {

namespace v1 = api::v1;

v1::LocalizerState ToApi(localization::LocalizerState state) {
  switch (state) {
    case localization::LocalizerState::kInitializing: return v1::INITIALIZING;
    case localization::LocalizerState::kLocalized: return v1::LOCALIZED;
    case localization::LocalizerState::kDegraded: return v1::DEGRADED;
    case localization::LocalizerState::kLost: return v1::LOST;
  }
  return v1::LOCALIZER_STATE_UNSPECIFIED;
}

void SetPose(const localization::Se2& pose, v1::Pose2D& out) {
  out.set_x(pose.translation().x());
  out.set_y(pose.translation().y());
  out.set_theta(pose.theta());
}

// The reply for a composed pose; the covariance field's 9 slots are reused, not regrown.
void FillPose(const ServedPose& served, v1::PoseReply& reply) {
  const localization::GlobalPose& pose = served.pose;
  const localization::LocalizationFix& fix = served.fix;
  reply.set_valid(pose.ok);
  reply.set_time_ns(pose.time_ns);
  reply.set_state(ToApi(pose.state));
  SetPose(pose.global_T_vehicle, *reply.mutable_global_t_vehicle());
  SetPose(fix.global_T_local, *reply.mutable_global_t_local());
  reply.mutable_covariance()->Resize(9, 0.0);
  for (int i = 0; i < 9; ++i) reply.set_covariance(i, pose.covariance(i / 3, i % 3));
  reply.set_since_accepted_match_s(fix.last_accepted_ns > 0
                                       ? static_cast<double>(pose.time_ns - fix.last_accepted_ns) * kSecondsPerNs
                                       : -1.0);
}

double AgeS(TimeNs now_ns, TimeNs newest_ns) {
  return newest_ns > 0 ? static_cast<double>(now_ns - newest_ns) * kSecondsPerNs : -1.0;
}

}  // namespace

void SetError(v1::Response& response, v1::Error::Code code, std::string message) {
  v1::Error& error = *response.mutable_error();
  error.set_code(code);
  error.set_message(std::move(message));
}

MapSummary SummarizeMap(const maps::PriorMapReader& map, std::string path) {
  const maps::PriorMapHeader& header = map.header();
  const double tile_m = header.resolution_m() * header.tile_cells();
  return {.path = std::move(path),
          .resolution_m = header.resolution_m(),
          .tiles = static_cast<std::uint32_t>(header.tiles_size()),
          .file_bytes = map.file_bytes(),
          .viewpoints = static_cast<std::uint32_t>(map.viewpoint_count()),
          .min_x = header.origin_x_m(),
          .min_y = header.origin_y_m(),
          .max_x = header.origin_x_m() + tile_m * header.width_tiles(),
          .max_y = header.origin_y_m() + tile_m * header.height_tiles()};
}

void ApiHandler::Handle(const v1::Request& request, v1::Response& response) {
  response.set_id(request.id());
  switch (request.kind_case()) {
    case v1::Request::kPoseNow: FillPoseNow(*response.mutable_pose()); return;
    case v1::Request::kPoseAt: HandlePoseAt(request.pose_at(), response); return;
    case v1::Request::kStatus: FillStatus(*response.mutable_status()); return;
    case v1::Request::kSetInitialPose: HandleSetPose(request.set_initial_pose(), response); return;
    case v1::Request::kMapInfo: FillMapInfo(*response.mutable_map_info()); return;
    case v1::Request::kSubscribe:  // the server's
    case v1::Request::KIND_NOT_SET: break;
  }
  SetError(response, v1::Error::MALFORMED, "the request names no kind");
}

void ApiHandler::FillPoseNow(v1::PoseReply& reply) const { FillPose(board_.ServeNow(), reply); }

void ApiHandler::HandlePoseAt(const v1::PoseAtRequest& request, v1::Response& response) const {
  const localization::PoseAtTime odometry = board_.OdometryAt(request.time_ns());
  if (!odometry.ok()) {
    const char* where = odometry.status == localization::QueryStatus::kBeforeWindow ? "before" : "after";
    if (odometry.status == localization::QueryStatus::kEmpty) {
      SetError(response, v1::Error::OUT_OF_WINDOW, "no odometry yet");
    } else {
      SetError(response, v1::Error::OUT_OF_WINDOW,
               "time " + std::to_string(request.time_ns()) + " is " +
                   std::to_string(static_cast<double>(odometry.outside_by_ns) * kSecondsPerNs) + " s " + where +
                   " the odometry window");
    }
    return;
  }
  const ServedPose served = board_.ServeAt(request.time_ns());
  if (!served.pose.ok) {
    SetError(response, v1::Error::NO_FIX, "no fix at that time");
    return;
  }
  FillPose(served, *response.mutable_pose());
}

void ApiHandler::HandleSetPose(const v1::SetInitialPoseRequest& request, v1::Response& response) {
  const v1::Pose2D& pose = request.global_t_vehicle();
  if (!request.has_global_t_vehicle() || !std::isfinite(pose.x()) || !std::isfinite(pose.y()) ||
      !std::isfinite(pose.theta())) {
    SetError(response, v1::Error::INVALID_ARGUMENT, "set_initial_pose needs a finite global_T_vehicle");
    return;
  }
  if (!(request.sigma_m() >= 0.0) || !(request.sigma_rad() >= 0.0) || !std::isfinite(request.sigma_m()) ||
      !std::isfinite(request.sigma_rad()) || request.time_ns() < 0) {
    SetError(response, v1::Error::INVALID_ARGUMENT, "sigmas must be finite and >= 0, time_ns >= 0");
    return;
  }
  const double sigma_m = request.sigma_m() > 0.0 ? request.sigma_m() : defaults_.sigma_m;
  const double sigma_rad = request.sigma_rad() > 0.0 ? request.sigma_rad() : defaults_.sigma_rad;
  InitialPoseRequest initial{.time_ns = request.time_ns(),
                             .global_T_vehicle = localization::Se2(Eigen::Vector2d(pose.x(), pose.y()), pose.theta()),
                             .covariance = Eigen::Vector3d(sigma_m * sigma_m, sigma_m * sigma_m, sigma_rad * sigma_rad)
                                               .asDiagonal()};
  set_pose_(initial);
  response.mutable_ack();
}

void ApiHandler::FillStatus(v1::Health& health) const {
  const HealthFigures figures = board_.health();
  const ServiceFigures service = figures_();
  health.set_state(ToApi(board_.fix().state));
  v1::SourceHealth& lidar = *health.mutable_lidar();
  lidar.set_rate_hz(service.lidar_rate_hz);
  lidar.set_received(service.lidar_received);
  lidar.set_dropped(service.lidar_dropped);
  lidar.set_malformed(figures.lidar_malformed);
  lidar.set_last_age_s(AgeS(service.now_ns, figures.newest_datagram_ns));
  v1::SourceHealth& can = *health.mutable_can();
  can.set_rate_hz(service.can_rate_hz);
  can.set_received(service.can_received);
  can.set_dropped(service.can_dropped);
  can.set_malformed(figures.can_malformed);
  can.set_last_age_s(AgeS(service.now_ns, figures.newest_frame_ns));
  health.set_revolutions(figures.revolutions);
  health.set_matches_accepted(figures.matches_accepted);
  health.set_matches_rejected(figures.matches_rejected);
  health.set_relocalizations(figures.relocalizations);
  health.set_match_ms_p50(figures.match_ms_p50);
  health.set_match_ms_p99(figures.match_ms_p99);
  health.set_solve_ms_p50(figures.solve_ms_p50);
  health.set_solve_ms_p99(figures.solve_ms_p99);
  health.set_graph_nodes(figures.graph_nodes);
  health.set_map_errors(figures.map_errors);
  health.set_rss_bytes(service.rss_bytes);
  health.set_uptime_s(service.uptime_s);
  health.set_clients(service.clients);
  health.set_malformed_requests(service.malformed_requests);
  health.set_last_error(service.last_error);
  *health.mutable_gpio() = service.gpio;
}

void ApiHandler::set_map(MapSummary map) {
  const std::lock_guard lock(map_mutex_);
  map_ = std::move(map);
}

void ApiHandler::FillMapInfo(v1::MapInfo& info) const {
  const std::lock_guard lock(map_mutex_);
  info.set_path(map_.path);
  info.set_resolution_m(map_.resolution_m);
  info.set_tiles(map_.tiles);
  info.set_file_bytes(map_.file_bytes);
  info.set_viewpoints(map_.viewpoints);
  info.set_min_x(map_.min_x);
  info.set_min_y(map_.min_y);
  info.set_max_x(map_.max_x);
  info.set_max_y(map_.max_y);
}

}  // namespace flat2d::daemon
