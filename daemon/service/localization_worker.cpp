#include "daemon/service/localization_worker.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

namespace flat2d::daemon {
namespace {

constexpr auto kIdleWait = std::chrono::milliseconds(100);

TimeNs SteadyNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Nearest-rank percentile of the first `count` values (copied: the ring keeps its order).
double Percentile(const std::array<double, 100>& values, std::size_t count, double fraction) {
  if (count == 0) return 0.0;
  std::array<double, 100> sorted = values;
  const auto rank = static_cast<std::size_t>(std::min<double>(count - 1, fraction * static_cast<double>(count)));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank),
                   sorted.begin() + static_cast<std::ptrdiff_t>(count));
  return sorted[rank];
}

}  // namespace

LocalizationWorker::LocalizationWorker(InputQueue& queue, PoseBoard& board,
                                       std::unique_ptr<localization::LocalizationPipeline> pipeline,
                                       std::optional<CanLogFollower> follower)
    : queue_(queue), board_(board), pipeline_(std::move(pipeline)), follower_(std::move(follower)) {
  pipeline_->set_revolution_handler(
      [this](const maps::PublishedGrid&, const localization::RevolutionReport& report) { OnRevolution(report); });
}

void LocalizationWorker::Run(std::stop_token stop) {
  while (!stop.stop_requested()) {
    heartbeat_.fetch_add(1, std::memory_order_relaxed);
    if (mail_.load(std::memory_order_acquire)) ServeMailboxes();
    queue_.PopNext(
        kIdleWait, [this](const QueuedDatagram& datagram) { OnDatagram(datagram); },
        [this](const hal::can::CanFrame& frame) { OnFrame(frame); });
    if (follower_)
      follower_->ReleaseThroughSilence(SteadyNowNs(), [this](const hal::can::CanFrame& frame) { OnFrame(frame); });
  }
}

void LocalizationWorker::RequestInitialPose(const InitialPoseRequest& request) {
  const std::lock_guard lock(mailbox_mutex_);
  pending_pose_ = request;
  mail_.store(true, std::memory_order_release);
  queue_.Wake();
}

void LocalizationWorker::ReplacePipeline(std::unique_ptr<localization::LocalizationPipeline> pipeline) {
  const std::lock_guard lock(mailbox_mutex_);
  pending_pipeline_ = std::move(pipeline);
  mail_.store(true, std::memory_order_release);
  queue_.Wake();
}

void LocalizationWorker::OnDatagram(const QueuedDatagram& datagram) {
  const hal::net::UdpDatagram view = datagram.view();
  if (follower_)
    follower_->ReleaseUntil(view.payload, SteadyNowNs(), [this](const hal::can::CanFrame& frame) { OnFrame(frame); });
  pipeline_->PushDatagram(view);
  health_.newest_datagram_ns = view.receive_time_ns;
}

void LocalizationWorker::OnFrame(const hal::can::CanFrame& frame) {
  const auto update = pipeline_->PushCan(frame);
  health_.newest_frame_ns = frame.time_ns;
  ++health_.can_frames;
  if (update && update->new_sample()) {
    board_.PushOdometry(update->sample);
    if (deferred_pose_) {
      const InitialPoseRequest request = *std::exchange(deferred_pose_, std::nullopt);
      pipeline_->localizer().SetInitialPose(request.time_ns != 0 ? request.time_ns : update->sample.time_ns,
                                            request.global_T_vehicle, request.covariance);
    }
  }
  board_.PublishFix(pipeline_->localizer().fix());
  // Through LiDAR silence the health figures keep coming, at 10 Hz of odometry time.
  if (frame.time_ns - last_publish_ns_ >= kHealthPeriodNs) Publish();
}

void LocalizationWorker::OnRevolution(const localization::RevolutionReport& report) {
  if (report.used) {
    const std::size_t slot = timings_ % kTimingWindow;
    match_ms_[slot] = report.match_s * 1e3;
    solve_ms_[slot] = report.solve_s * 1e3;
    ++timings_;
  }
  Publish();
}

void LocalizationWorker::Publish() {
  const localization::LocalizerStats& stats = pipeline_->localizer().stats();
  const std::size_t count = std::min(timings_, kTimingWindow);
  health_.revolutions = stats.grids;
  health_.matches_accepted = stats.matches_accepted;
  health_.matches_rejected = stats.matches_rejected;
  health_.relocalizations = stats.relocalizations;
  health_.map_errors = stats.map_errors;
  health_.match_ms_p50 = Percentile(match_ms_, count, 0.5);
  health_.match_ms_p99 = Percentile(match_ms_, count, 0.99);
  health_.solve_ms_p50 = Percentile(solve_ms_, count, 0.5);
  health_.solve_ms_p99 = Percentile(solve_ms_, count, 0.99);
  health_.graph_nodes = static_cast<std::uint32_t>(pipeline_->localizer().graph_nodes());
  health_.lidar_malformed = pipeline_->stream().stats().malformed;
  const auto& decoder = pipeline_->odometry().mapper().decoder_stats();
  health_.can_malformed = decoder.checksum_failures + decoder.too_short + pipeline_->odometry().mapper().stats().non_finite;
  board_.PublishHealth(health_);
  board_.PublishFix(pipeline_->localizer().fix());
  last_publish_ns_ = health_.newest_frame_ns;
}

void LocalizationWorker::ServeMailboxes() {
  std::optional<InitialPoseRequest> pose;
  std::unique_ptr<localization::LocalizationPipeline> replacement;
  {
    const std::lock_guard lock(mailbox_mutex_);
    pose = std::exchange(pending_pose_, std::nullopt);
    replacement = std::move(pending_pipeline_);
    mail_.store(false, std::memory_order_release);
  }
  if (replacement) {
    // The new pipeline's odometry starts from scratch: carry the global pose over.
    const localization::GlobalPose now = board_.PoseNow();
    pipeline_ = std::move(replacement);
    pipeline_->set_revolution_handler(
        [this](const maps::PublishedGrid&, const localization::RevolutionReport& report) { OnRevolution(report); });
    board_.ClearOdometry();
    if (now.ok && !pose) pose = InitialPoseRequest{0, now.global_T_vehicle, now.covariance};
  }
  if (pose) ApplyInitialPose(*pose);
}

void LocalizationWorker::ApplyInitialPose(const InitialPoseRequest& request) {
  const TimeNs newest_ns = board_.newest_odometry_ns();
  if (request.time_ns == 0 && newest_ns == 0) {
    deferred_pose_ = request;
    return;
  }
  pipeline_->localizer().SetInitialPose(request.time_ns != 0 ? request.time_ns : newest_ns, request.global_T_vehicle,
                                        request.covariance);
}

}  // namespace flat2d::daemon
