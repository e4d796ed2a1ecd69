// The Velodyne front end: UDP datagrams in, timestamped revolutions of fans out.
//
// Steps per datagram: classify by size and port (1206-byte data, 512-byte position,
// anything else on the sensor's ports is malformed); until the model is known, hold the
// first data packets in a fixed buffer and let ModelIdentifier decide; decode each data
// packet into fans (PacketDecoder); check device time against the previous packet to
// count out-of-order packets (dropped), lost packets (time and azimuth gap) and pauses
// (time gap only, e.g. a FOV-limited sensor); resolve the hour-relative device time to
// absolute time (SensorClock, disciplined by position packets when present); feed the
// fans to the RevolutionAssembler and hand each completed revolution to the handler.
// Bad input is counted by reason and never stops the stream. After the model is known,
// Push allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "hal/common/error.hpp"
#include "hal/net/udp_datagram.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "hal/velodyne/model_identifier.hpp"
#include "hal/velodyne/packet_decoder.hpp"
#include "hal/velodyne/packet_layout.hpp"
#include "hal/velodyne/position_packet.hpp"
#include "hal/velodyne/revolution.hpp"
#include "hal/velodyne/sensor_clock.hpp"

namespace flat2d::hal::velodyne {

struct VelodyneStreamOptions {
  std::optional<Model> model;              // configured model; else identified from packets
  std::optional<LaserTable> calibration;   // replaces the built-in table (and fixes the model)
  RevolutionOptions revolution;
  std::uint16_t data_port = kDefaultDataPort;          // 0: any port
  std::uint16_t position_port = kDefaultPositionPort;  // 0: any port
};

struct VelodyneStreamStats {
  std::uint64_t data_packets = 0;      // 1206-byte payloads, decodable or not
  std::uint64_t position_packets = 0;  // 512-byte payloads that decoded
  std::uint64_t points = 0;            // channel records with a return, both returns in dual
  std::uint64_t revolutions = 0;       // complete revolutions (cut to cut)
  std::uint64_t partial_revolutions = 0;
  std::uint64_t malformed = 0;         // sum of the reasons below
  std::uint64_t wrong_size = 0;        // on a sensor port but neither 1206 nor 512 bytes
  std::uint64_t bad_block_flag = 0;
  std::uint64_t bad_azimuth = 0;
  std::uint64_t unknown_return_mode = 0;
  std::uint64_t bad_position_packets = 0;
  std::uint64_t undecodable_model = 0;  // data packets of an unsupported model
  std::uint64_t out_of_order = 0;       // device time not after the previous packet: dropped
  std::uint64_t lost_packets = 0;       // estimated from time and azimuth gaps
  std::uint64_t pauses = 0;             // time gaps without an azimuth gap
  std::uint64_t dropped_fans = 0;       // revolution buffer full
  std::uint64_t ignored = 0;            // datagrams to other ports
};

class VelodyneStream {
 public:
  using RevolutionHandler = std::function<void(const Revolution&)>;

  explicit VelodyneStream(VelodyneStreamOptions options, RevolutionHandler handler = {});
  ~VelodyneStream();
  VelodyneStream(const VelodyneStream&) = delete;
  VelodyneStream& operator=(const VelodyneStream&) = delete;

  void Push(const net::UdpDatagram& datagram);
  // End of input: decides the model if still pending and publishes the partial
  // revolution being assembled.
  void Finish();

  const VelodyneStreamStats& stats() const { return stats_; }
  // Set once the model is decided.
  const std::optional<Identification>& identification() const { return identification_; }
  // Set when the model cannot be decoded (unsupported product); the stream then only counts.
  const std::optional<Error>& model_error() const { return model_error_; }
  // The name of the product that model_error() refers to, e.g. "VLS-128".
  std::string unsupported_product() const { return ProductIdName(identifier_.product_id()); }
  const std::optional<PositionPacket>& last_position() const { return last_position_; }
  const SensorClock& clock() const { return clock_; }

 private:
  struct PendingPacket {
    std::array<std::uint8_t, kDataPacketSize> bytes;
    TimeNs receive_time_ns;
  };

  bool IsDataPort(std::uint16_t port) const;
  bool IsPositionPort(std::uint16_t port) const;
  void OnPositionPacket(std::span<const std::uint8_t> payload);
  void OnDataPacket(std::span<const std::uint8_t> payload, TimeNs receive_time_ns);
  void DecideModel();
  void DecodeAndAssemble(std::span<const std::uint8_t> payload, TimeNs receive_time_ns);
  bool CheckSequence(const DecodedPacket& packet);
  void CountError(PacketError error);
  void Emit(const Revolution* revolution);

  VelodyneStreamOptions options_;
  RevolutionHandler handler_;
  VelodyneStreamStats stats_;
  ModelIdentifier identifier_;
  std::array<PendingPacket, ModelIdentifier::kPacketsToDecide> pending_{};
  int pending_count_ = 0;
  std::optional<Identification> identification_;
  std::optional<Error> model_error_;
  std::unique_ptr<PacketDecoder> decoder_;
  std::unique_ptr<RevolutionAssembler> assembler_;
  std::unique_ptr<DecodedPacket> packet_;  // ~22 KB: kept off the stack
  SensorClock clock_;
  std::optional<PositionPacket> last_position_;
  std::optional<std::uint32_t> previous_us_past_hour_;
  float previous_last_azimuth_rad_ = 0.0f;
  double packet_period_us_ = 0.0;
};

}  // namespace flat2d::hal::velodyne
