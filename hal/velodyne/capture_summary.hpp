// Summary of a Velodyne capture: what the sensor is, what the packets decoded to, and
// what went wrong, with one revolution's fans kept for rendering.
//
// Runs a VelodyneStream over a DatagramSource (pcap, pcapng or raw payload dump) to the
// end. This is the offline counterpart of the daemon's ingest and the engine of
// `flat2d-inspect`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/velodyne_stream.hpp"

namespace flat2d::hal::velodyne {

struct RevolutionSummary {
  std::uint64_t sequence = 0;
  bool complete = false;
  std::size_t fans = 0;
  int points = 0;
  TimeNs start_ns = 0;
  TimeNs end_ns = 0;
  double swept_azimuth_deg = 0.0;
  float max_range_m = 0.0f;
  bool stamps_monotonic = true;  // fan stamps never decrease within the revolution
};

struct CaptureSummary {
  std::string product;  // decoded model name, or the unsupported product's name
  std::optional<Identification> identification;
  std::optional<Error> model_error;
  VelodyneStreamStats stream;
  net::CaptureStats capture;
  std::vector<RevolutionSummary> revolutions;  // complete and partial, in order
  std::optional<PositionPacket> last_position;
  TimeSource time_source = TimeSource::kSensorOnly;
  std::vector<Fan> kept_revolution;  // fans of the revolution chosen in the options
};

struct CaptureSummaryOptions {
  VelodyneStreamOptions stream;
  // Which complete revolution to keep (0-based); when the capture has fewer complete
  // ones, the largest partial one is kept instead.
  std::size_t keep_revolution = 0;
};

CaptureSummary SummarizeCapture(net::DatagramSource& source, const CaptureSummaryOptions& options);

}  // namespace flat2d::hal::velodyne
