// Answers one API request (daemon/api/flat2d_api.proto) from the pose board, the map's
// header and the daemon's counters; the server (api_server.hpp) owns sockets, framing and
// subscriptions. Validation is layered as chrony's command socket: the frame parsed, a kind
// named, the arguments finite and in range; then read-only requests are answered and the
// one mutating request (set_initial_pose) goes to the localization thread's mailbox.
#pragma once

#include <functional>
#include <mutex>
#include <string>

#include "daemon/api/flat2d_api.pb.h"
#include "daemon/service/localization_worker.hpp"
#include "daemon/service/pose_board.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::daemon {

// Figures the handler does not own: the sources' rates, the server's own counts, memory.
struct ServiceFigures {
  double lidar_rate_hz = 0.0;
  double can_rate_hz = 0.0;
  std::uint64_t lidar_received = 0;
  std::uint64_t lidar_dropped = 0;
  std::uint64_t can_received = 0;
  std::uint64_t can_dropped = 0;
  std::uint32_t clients = 0;
  std::uint64_t malformed_requests = 0;
  std::uint64_t rss_bytes = 0;
  double uptime_s = 0.0;
  TimeNs now_ns = 0;  // wall clock, for the sources' ages
  std::string last_error;
  api::v1::GpioHealth gpio;
};

struct MapSummary {
  std::string path;
  double resolution_m = 0.0;
  std::uint32_t tiles = 0;
  std::uint64_t file_bytes = 0;
  std::uint32_t viewpoints = 0;
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;
};

MapSummary SummarizeMap(const maps::PriorMapReader& map, std::string path);

struct InitialPoseDefaults {
  double sigma_m = 1.0;
  double sigma_rad = 0.1;
};

class ApiHandler {
 public:
  using FiguresSource = std::function<ServiceFigures()>;
  using PoseSink = std::function<void(const InitialPoseRequest&)>;

  ApiHandler(const PoseBoard& board, MapSummary map, InitialPoseDefaults defaults, PoseSink set_pose,
             FiguresSource figures)
      : board_(board), map_(std::move(map)), defaults_(defaults), set_pose_(std::move(set_pose)),
        figures_(std::move(figures)) {}

  // Fills `response` (id echoed) for every kind but subscribe, which the server handles.
  void Handle(const api::v1::Request& request, api::v1::Response& response);
  // The newest pose, as a subscription update.
  void FillPoseNow(api::v1::PoseReply& reply) const;
  void set_map(MapSummary map);  // after a reload; any thread

 private:
  void HandlePoseAt(const api::v1::PoseAtRequest& request, api::v1::Response& response) const;
  void HandleSetPose(const api::v1::SetInitialPoseRequest& request, api::v1::Response& response);
  void FillStatus(api::v1::Health& health) const;
  void FillMapInfo(api::v1::MapInfo& info) const;

  const PoseBoard& board_;
  mutable std::mutex map_mutex_;
  MapSummary map_;
  InitialPoseDefaults defaults_;
  PoseSink set_pose_;
  FiguresSource figures_;
};

void SetError(api::v1::Response& response, api::v1::Error::Code code, std::string message);

}  // namespace flat2d::daemon
