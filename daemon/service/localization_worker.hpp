// The localization thread (DESIGN.md "Threads": matcher + graph): takes datagrams and CAN
// frames from the input queue in arrival order, runs them through the localization pipeline
// (localization_pipeline.hpp, the code flat2d-localize replays), and publishes odometry,
// the fix and health figures to the pose board after every input.
//
// Other threads talk to it through two mailboxes read between inputs: an initial pose
// (from a client, applied at the newest odometry time or the one it names) and a new
// pipeline (a SIGHUP reload, whose odometry frame starts afresh: the current global pose is
// carried over as its initial pose). Its heartbeat advances on every loop, input or not, so
// the supervisor can tell a stuck thread from a quiet one.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <stop_token>

#include "daemon/service/can_log_follower.hpp"
#include "daemon/service/input_queue.hpp"
#include "daemon/service/pose_board.hpp"
#include "localization/localizer/localization_pipeline.hpp"

namespace flat2d::daemon {

struct InitialPoseRequest {
  TimeNs time_ns = 0;  // 0: at the newest odometry sample
  localization::Se2 global_T_vehicle;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

class LocalizationWorker {
 public:
  // `follower`: a candump log replayed on the LiDAR's clock instead of a CAN thread.
  LocalizationWorker(InputQueue& queue, PoseBoard& board, std::unique_ptr<localization::LocalizationPipeline> pipeline,
                     std::optional<CanLogFollower> follower);

  void Run(std::stop_token stop);  // the thread's body

  // Any thread.
  void RequestInitialPose(const InitialPoseRequest& request);
  void ReplacePipeline(std::unique_ptr<localization::LocalizationPipeline> pipeline);
  std::uint64_t heartbeat() const { return heartbeat_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::size_t kTimingWindow = 100;  // revolutions in the p50/p99 figures
  static constexpr TimeNs kHealthPeriodNs = 100 * kNsPerMs;

  void OnDatagram(const QueuedDatagram& datagram);
  void OnFrame(const hal::can::CanFrame& frame);
  void OnRevolution(const localization::RevolutionReport& report);
  void ServeMailboxes();
  void Publish();
  void ApplyInitialPose(const InitialPoseRequest& request);

  InputQueue& queue_;
  PoseBoard& board_;
  std::unique_ptr<localization::LocalizationPipeline> pipeline_;
  std::optional<CanLogFollower> follower_;
  std::atomic<std::uint64_t> heartbeat_{0};

  std::mutex mailbox_mutex_;
  std::optional<InitialPoseRequest> pending_pose_;
  std::unique_ptr<localization::LocalizationPipeline> pending_pipeline_;
  std::atomic<bool> mail_{false};
  // A pose asked for before there was odometry: applied at the first sample.
  std::optional<InitialPoseRequest> deferred_pose_;

  HealthFigures health_;
  std::array<double, kTimingWindow> match_ms_{};
  std::array<double, kTimingWindow> solve_ms_{};
  std::size_t timings_ = 0;
  TimeNs last_publish_ns_ = 0;  // revolutions recorded, the ring's write position modulo its size
};

}  // namespace flat2d::daemon
