#include "hal/velodyne/capture_summary.hpp"

#include <algorithm>

#include "hal/common/angles.hpp"

namespace flat2d::hal::velodyne {
namespace {

RevolutionSummary Summarize(const Revolution& revolution) {
  RevolutionSummary summary;
  summary.sequence = revolution.sequence;
  summary.complete = revolution.complete;
  summary.fans = revolution.fans.size();
  summary.points = revolution.points;
  summary.start_ns = revolution.start_ns();
  summary.end_ns = revolution.end_ns();
  summary.swept_azimuth_deg = revolution.swept_azimuth_rad * kRadToDeg;
  for (std::size_t f = 0; f < revolution.fans.size(); ++f) {
    const Fan& fan = revolution.fans[f];
    if (f > 0 && fan.stamp_ns < revolution.fans[f - 1].stamp_ns) summary.stamps_monotonic = false;
    for (int laser = 0; laser < fan.num_lasers; ++laser) {
      summary.max_range_m = std::max(summary.max_range_m, fan.returns[static_cast<std::size_t>(laser)].range_m);
    }
  }
  return summary;
}

}  // namespace

CaptureSummary SummarizeCapture(net::DatagramSource& source, const CaptureSummaryOptions& options) {
  CaptureSummary summary;
  std::size_t complete_seen = 0;
  bool kept_complete = false;
  auto on_revolution = [&](const Revolution& revolution) {
    summary.revolutions.push_back(Summarize(revolution));
    if (kept_complete) return;
    if (revolution.complete && complete_seen++ == options.keep_revolution) {
      summary.kept_revolution = revolution.fans;
      kept_complete = true;
    } else if (revolution.fans.size() > summary.kept_revolution.size()) {
      summary.kept_revolution = revolution.fans;  // fallback: the largest so far
    }
  };
  VelodyneStream stream(options.stream, on_revolution);
  while (std::optional<net::UdpDatagram> datagram = source.Next()) stream.Push(*datagram);
  stream.Finish();

  summary.stream = stream.stats();
  summary.capture = source.stats();
  summary.identification = stream.identification();
  summary.model_error = stream.model_error();
  summary.last_position = stream.last_position();
  summary.time_source = stream.clock().source();
  if (summary.identification) {
    summary.product = std::string(ModelName(summary.identification->model));
  } else if (summary.model_error) {
    summary.product = stream.unsupported_product();
  }
  return summary;
}

}  // namespace flat2d::hal::velodyne
