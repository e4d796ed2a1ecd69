#include "localization/tools/localize_run.hpp"

#include <chrono>
#include <thread>
#include <utility>

#include "hal/can/candump_log.hpp"
#include "hal/can/dbc.hpp"
#include "hal/common/time.hpp"
#include "hal/net/datagram_source.hpp"
#include "localization/localizer/localization_pipeline.hpp"
#include "localization/odometry/odometry_config.hpp"

namespace flat2d::localization {
namespace {

// Sleeps until the input's time has come, relative to the first input (realtime replay).
class Pacer {
 public:
  explicit Pacer(bool enabled) : enabled_(enabled) {}
  void WaitFor(TimeNs time_ns) {
    if (!enabled_) return;
    if (!started_) {
      started_ = true;
      first_ns_ = time_ns;
      wall_start_ = std::chrono::steady_clock::now();
      return;
    }
    std::this_thread::sleep_until(wall_start_ + std::chrono::nanoseconds(time_ns - first_ns_));
  }

 private:
  bool enabled_;
  bool started_ = false;
  TimeNs first_ns_ = 0;
  std::chrono::steady_clock::time_point wall_start_;
};

}  // namespace

Result<Se2> InitialPoseAt(const InitialPoseOptions& initial, double time_s, const std::string& what) {
  Se2 pose;
  if (initial.pose) {
    pose = *initial.pose;
  } else if (!evaluation::PoseAt(initial.track, time_s, 1.0, pose)) {
    return MakeError("the initial-pose track does not cover the " + what + "'s time");
  }
  return Se2(pose.translation() + initial.offset.head<2>(), pose.theta() + initial.offset.z());
}

Result<LocalizeRunResult> RunLocalization(const LocalizeRunOptions& options) {
  if (!options.initial.pose && options.initial.track.empty()) return MakeError("no initial pose given");
  auto dbc = hal::can::LoadDbc(options.dbc);
  if (!dbc.ok()) return dbc.error();
  auto odometry_config = LoadOdometryConfig(options.odometry_config);
  if (!odometry_config.ok()) return odometry_config.error();
  auto map = maps::PriorMapReader::Open(options.map, options.localizer.map_cache_tiles);
  if (!map.ok()) return map.error();
  auto can = hal::can::CandumpReader::Open(options.can_log);
  if (!can.ok()) return can.error();
  auto capture = hal::net::OpenCapture(options.capture);
  if (!capture.ok()) return capture.error();

  LocalizationPipelineOptions pipeline_options;
  pipeline_options.stream = options.stream;
  pipeline_options.grid = options.grid;
  pipeline_options.localizer = options.localizer;
  auto pipeline = LocalizationPipeline::Create(*dbc, *odometry_config, std::move(*map), pipeline_options);
  if (!pipeline.ok()) return pipeline.error();
  LocalizationPipeline& localization = **pipeline;

  LocalizeRunResult result;
  localization.set_revolution_handler([&](const maps::PublishedGrid& grid, const RevolutionReport& report) {
    result.revolutions.push_back({static_cast<double>(grid.start_ns) * kSecondsPerNs, report});
  });
  bool initialized = false;
  Se2 global_T_local;  // the initial pose's, for the open-loop odometry
  std::optional<Error> failure;
  auto on_frame = [&](const hal::can::CanFrame& frame) {
    const auto update = localization.PushCan(frame);
    if (!update || !update->new_sample()) return;
    const OdometrySample& sample = update->sample;
    if (!initialized) {
      initialized = true;
      const Result<Se2> pose =
          InitialPoseAt(options.initial, static_cast<double>(sample.time_ns) * kSecondsPerNs, "first odometry sample");
      if (!pose.ok()) {
        failure = pose.error();
        return;
      }
      const Eigen::Vector3d sigma(options.initial.sigma_m, options.initial.sigma_m, options.initial.sigma_rad);
      localization.localizer().SetInitialPose(sample.time_ns, *pose, sigma.cwiseAbs2().asDiagonal());
      result.first_fix_s = static_cast<double>(sample.time_ns) * kSecondsPerNs;
      global_T_local = *pose * sample.local_T_vehicle.Inverse();
    }
    result.odometry.push_back({static_cast<double>(sample.time_ns) * kSecondsPerNs, global_T_local * sample.local_T_vehicle});
    const GlobalPose pose = localization.PoseAt(sample.time_ns);
    if (pose.ok) result.estimate.push_back({static_cast<double>(sample.time_ns) * kSecondsPerNs, pose.global_T_vehicle});
  };

  // Merge by time: the earlier of the next frame and the next datagram goes first.
  Pacer pacer(options.realtime);
  hal::can::CanFrame frame;
  bool have_frame = can->Next(frame);
  std::optional<hal::net::UdpDatagram> datagram = (*capture)->Next();
  while ((have_frame || datagram) && !failure) {
    if (have_frame && (!datagram || frame.time_ns <= datagram->receive_time_ns)) {
      pacer.WaitFor(frame.time_ns);
      on_frame(frame);
      have_frame = can->Next(frame);
    } else {
      pacer.WaitFor(datagram->receive_time_ns);
      localization.PushDatagram(*datagram);
      datagram = (*capture)->Next();
    }
  }
  if (failure) return *failure;
  localization.Finish();
  if (localization.failure()) return *localization.failure();
  if (localization.stream().model_error()) {
    return MakeError(options.capture.string() + ": " + localization.stream().model_error()->message);
  }
  result.stats = localization.localizer().stats();
  return result;
}

}  // namespace flat2d::localization
