// Where a simulated drive goes: files a user exchanges, or a live UDP stream.
//
// FileSink writes the drive in the field's formats into one directory: lidar.pcap
// (Ethernet/IPv4/UDP frames with nanosecond capture times, PcapWriter), can.log (candump
// -l, CandumpWriter), vehicle.dbc (the DBC the frames follow), truth.tum (world_T_vehicle
// at the truth rate, TumWriter) and truth_map.pgm + truth_map.yaml (the world's true 2D
// structure, ROS map_server convention). Open creates the directory and every file before
// the simulation starts, so an unwritable directory fails at once, not after a long run.
//
// LiveSink sends the LiDAR datagrams to a UDP address as the sensor would, paced to real
// time (or `speed` times it) on a monotonic clock with absolute deadlines, so that a slow
// packet does not delay the ones after it; CAN frames and truth poses are not sent.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "hal/can/candump_log.hpp"
#include "hal/net/pcap_writer.hpp"
#include "hal/net/replay.hpp"
#include "hal/net/udp_sender.hpp"
#include "hal/sim/simulation.hpp"
#include "hal/sim/truth_map.hpp"
#include "hal/sim/tum_writer.hpp"

namespace flat2d::hal::sim {

// File names inside the output directory.
inline constexpr const char* kLidarFile = "lidar.pcap";
inline constexpr const char* kCanFile = "can.log";
inline constexpr const char* kDbcFile = "vehicle.dbc";
inline constexpr const char* kTruthFile = "truth.tum";
inline constexpr const char* kTruthMapStem = "truth_map";  // .pgm and .yaml

struct FileSinkOptions {
  bool truth_map = true;        // write truth_map.pgm/.yaml in Begin
  TruthMapOptions truth_map_options;  // resolution, margin, class thresholds
};

class FileSink final : public SimulationSink {
 public:
  static Result<FileSink> Open(const std::filesystem::path& directory,
                               const FileSinkOptions& options = {});

  FileSink(FileSink&&) noexcept = default;
  FileSink& operator=(FileSink&&) noexcept = default;
  ~FileSink() override = default;

  Status Begin(const SimulationSetup& setup) override;
  Status OnDatagram(const net::UdpDatagram& datagram) override;
  Status OnCanFrame(const can::CanFrame& frame) override;
  Status OnTruthPose(TimeNs time_ns, const VehicleState& state) override;
  Status Finish() override;

  const std::filesystem::path& directory() const { return directory_; }

 private:
  FileSink(std::filesystem::path directory, FileSinkOptions options, net::PcapWriter pcap,
           can::CandumpWriter can, TumWriter truth)
      : directory_(std::move(directory)),
        options_(options),
        pcap_(std::move(pcap)),
        can_(std::move(can)),
        truth_(std::move(truth)) {}

  std::filesystem::path directory_;
  FileSinkOptions options_;
  net::PcapWriter pcap_;
  can::CandumpWriter can_;
  TumWriter truth_;
};

struct LiveSinkOptions {
  net::UdpSenderOptions sender;  // destination host; each datagram keeps its own port
  double speed = 1.0;            // 2: twice real time; <= 0: as fast as possible
};

class LiveSink final : public SimulationSink {
 public:
  // `clock` must outlive the sink; null uses the monotonic clock.
  static Result<LiveSink> Open(const LiveSinkOptions& options, net::ReplayClock* clock = nullptr);

  Status OnDatagram(const net::UdpDatagram& datagram) override;

  std::uint64_t sent() const { return sent_; }
  // Failed sends are counted, not fatal (a receiver may come and go).
  std::uint64_t send_errors() const { return send_errors_; }
  const std::string& first_send_error() const { return first_send_error_; }

 private:
  LiveSink(net::UdpSender sender, double speed, net::ReplayClock* clock);

  net::UdpSender sender_;
  double speed_;
  std::unique_ptr<net::MonotonicReplayClock> own_clock_;
  net::ReplayClock* clock_;
  std::optional<TimeNs> first_time_ns_;
  TimeNs start_clock_ns_ = 0;
  std::uint64_t sent_ = 0;
  std::uint64_t send_errors_ = 0;
  std::string first_send_error_;
};

}  // namespace flat2d::hal::sim
