#include "hal/sim/simulation_sinks.hpp"

#include <cmath>
#include <fstream>
#include <system_error>

#include "hal/sim/truth_map.hpp"
#include "hal/sim/vehicle_dbc.hpp"

namespace flat2d::hal::sim {
namespace {

Status WriteTextFile(const std::filesystem::path& path, std::string_view text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.close();
  if (!file) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

}  // namespace

Result<FileSink> FileSink::Open(const std::filesystem::path& directory,
                                const FileSinkOptions& options) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) return MakeError(directory.string() + ": cannot create directory: " + error.message());
  if (!std::filesystem::is_directory(directory)) {
    return MakeError(directory.string() + ": not a directory");
  }
  auto pcap = net::PcapWriter::Create(directory / kLidarFile);
  if (!pcap.ok()) return pcap.error();
  auto can_log = can::CandumpWriter::Open(directory / kCanFile);
  if (!can_log.ok()) return can_log.error();
  auto truth = TumWriter::Open(directory / kTruthFile);
  if (!truth.ok()) return truth.error();
  return FileSink(directory, options, std::move(*pcap), std::move(*can_log), std::move(*truth));
}

Status FileSink::Begin(const SimulationSetup& setup) {
  if (Status dbc = WriteTextFile(directory_ / kDbcFile, VehicleDbcText()); !dbc) return dbc;
  if (!options_.truth_map) return Status::Ok();
  auto map = RasterizeTruthMap(setup.scene, options_.truth_map_options);
  if (!map.ok()) return map.error();
  return WriteTruthMap(*map, directory_ / kTruthMapStem);
}

Status FileSink::OnDatagram(const net::UdpDatagram& datagram) { return pcap_.Write(datagram); }

Status FileSink::OnCanFrame(const can::CanFrame& frame) { return can_.Write(frame); }

Status FileSink::OnTruthPose(TimeNs time_ns, const VehicleState& state) {
  return truth_.Write(time_ns, state.world_T_vehicle);
}

Status FileSink::Finish() {
  Status pcap = pcap_.Close();
  Status can_log = can_.Close();
  Status truth = truth_.Close();
  if (!pcap) return pcap;
  if (!can_log) return can_log;
  return truth;
}

LiveSink::LiveSink(net::UdpSender sender, double speed, net::ReplayClock* clock)
    : sender_(std::move(sender)), speed_(speed), clock_(clock) {
  if (clock_ == nullptr) {
    own_clock_ = std::make_unique<net::MonotonicReplayClock>();
    clock_ = own_clock_.get();
  }
}

Result<LiveSink> LiveSink::Open(const LiveSinkOptions& options, net::ReplayClock* clock) {
  net::UdpSenderOptions sender_options = options.sender;
  sender_options.keep_datagram_port = true;
  if (sender_options.destination.address == net::kIpv4Broadcast) {
    sender_options.allow_broadcast = true;
  }
  auto sender = net::UdpSender::Open(sender_options);
  if (!sender.ok()) return sender.error();
  return LiveSink(std::move(*sender), options.speed, clock);
}

Status LiveSink::OnDatagram(const net::UdpDatagram& datagram) {
  if (!first_time_ns_) {
    first_time_ns_ = datagram.receive_time_ns;
    start_clock_ns_ = clock_->Now();
  }
  if (speed_ > 0.0) {
    // Absolute deadline: start + (simulated offset) / speed, as replay.hpp schedules.
    const double offset_ns = static_cast<double>(datagram.receive_time_ns - *first_time_ns_) / speed_;
    const TimeNs deadline_ns = start_clock_ns_ + std::llround(offset_ns);
    if (deadline_ns > clock_->Now()) clock_->SleepUntil(deadline_ns);
  }
  // A lost datagram is what a live network does; count it and keep the schedule.
  if (Status sent = sender_.Send(datagram); sent) {
    ++sent_;
  } else {
    if (send_errors_ == 0) first_send_error_ = sent.error().message;
    ++send_errors_;
  }
  return Status::Ok();
}

}  // namespace flat2d::hal::sim
