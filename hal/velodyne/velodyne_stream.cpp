#include "hal/velodyne/velodyne_stream.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "hal/velodyne/firing_timing.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double ForwardAngle(float from, float to) {
  const double delta = std::fmod(static_cast<double>(to) - static_cast<double>(from), kTwoPi);
  return delta < 0.0 ? delta + kTwoPi : delta;
}

}  // namespace

VelodyneStream::VelodyneStream(VelodyneStreamOptions options, RevolutionHandler handler)
    : options_(std::move(options)),
      handler_(std::move(handler)),
      identifier_(options_.calibration ? std::optional(options_.calibration->model)
                                       : options_.model),
      packet_(std::make_unique<DecodedPacket>()) {}

VelodyneStream::~VelodyneStream() = default;

bool VelodyneStream::IsDataPort(std::uint16_t port) const {
  return options_.data_port == 0 || port == 0 || port == options_.data_port;
}

bool VelodyneStream::IsPositionPort(std::uint16_t port) const {
  return options_.position_port == 0 || port == 0 || port == options_.position_port;
}

void VelodyneStream::Push(const net::UdpDatagram& datagram) {
  const std::size_t size = datagram.payload.size();
  const std::uint16_t port = datagram.destination.port;
  if (size == kDataPacketSize && IsDataPort(port)) {
    OnDataPacket(datagram.payload, datagram.receive_time_ns);
  } else if (size == kPositionPacketSize && IsPositionPort(port)) {
    OnPositionPacket(datagram.payload);
  } else if ((options_.data_port != 0 && port == options_.data_port) ||
             (options_.position_port != 0 && port == options_.position_port) || port == 0) {
    ++stats_.wrong_size;
    ++stats_.malformed;
  } else {
    ++stats_.ignored;
  }
}

void VelodyneStream::OnPositionPacket(std::span<const std::uint8_t> payload) {
  Result<PositionPacket> position = DecodePositionPacket(payload);
  if (!position.ok()) {
    ++stats_.bad_position_packets;
    ++stats_.malformed;
    return;
  }
  ++stats_.position_packets;
  clock_.ObservePositionPacket(*position);
  last_position_ = std::move(position).value();
}

void VelodyneStream::OnDataPacket(std::span<const std::uint8_t> payload, TimeNs receive_time_ns) {
  ++stats_.data_packets;
  if (model_error_) {
    ++stats_.undecodable_model;
    return;
  }
  if (!identification_) {
    identifier_.Observe(payload);
    PendingPacket& pending = pending_[static_cast<std::size_t>(pending_count_++)];
    std::memcpy(pending.bytes.data(), payload.data(), kDataPacketSize);
    pending.receive_time_ns = receive_time_ns;
    if (identifier_.ReadyToDecide()) DecideModel();
    return;
  }
  DecodeAndAssemble(payload, receive_time_ns);
}

void VelodyneStream::DecideModel() {
  Result<Identification> decided = identifier_.Decide();
  if (!decided.ok()) {
    model_error_ = decided.error();
    stats_.undecodable_model += static_cast<std::uint64_t>(pending_count_);
    pending_count_ = 0;
    return;
  }
  identification_ = std::move(decided).value();
  const Model model = identification_->model;
  const LaserTable table = options_.calibration ? *options_.calibration : DefaultLaserTable(model);
  decoder_ = std::make_unique<PacketDecoder>(table);
  assembler_ = std::make_unique<RevolutionAssembler>(options_.revolution, model,
                                                     identification_->return_mode);
  packet_period_us_ = PacketPeriodUs(model, identification_->return_mode);
  for (int i = 0; i < pending_count_; ++i) {
    const PendingPacket& pending = pending_[static_cast<std::size_t>(i)];
    DecodeAndAssemble(pending.bytes, pending.receive_time_ns);
  }
  pending_count_ = 0;
}

void VelodyneStream::DecodeAndAssemble(std::span<const std::uint8_t> payload,
                                       TimeNs receive_time_ns) {
  DecodedPacket& packet = *packet_;
  decoder_->Decode(payload, packet);
  if (packet.error != PacketError::kNone) {
    CountError(packet.error);
    return;
  }
  if (!CheckSequence(packet)) return;

  const TimeNs packet_time_ns = clock_.Resolve(packet.us_past_hour, receive_time_ns);
  for (int f = 0; f < packet.num_fans; ++f) packet.fans[static_cast<std::size_t>(f)].stamp_ns += packet_time_ns;
  stats_.points += static_cast<std::uint64_t>(packet.num_points);
  previous_last_azimuth_rad_ = packet.fans[static_cast<std::size_t>(packet.num_fans - 1)].azimuth_rad;
  Emit(assembler_->Add(std::span(packet.fans.data(), static_cast<std::size_t>(packet.num_fans))));
}

// Orders packets by device time: out-of-order and duplicate packets are dropped; a gap
// of more than 1.5 packet periods is loss if the azimuth jumped with it (the rotor kept
// turning while packets were lost) and a pause otherwise (no packets were sent).
bool VelodyneStream::CheckSequence(const DecodedPacket& packet) {
  if (!previous_us_past_hour_) {
    previous_us_past_hour_ = packet.us_past_hour;
    return true;
  }
  const std::int64_t step_us = DeviceStepUs(*previous_us_past_hour_, packet.us_past_hour);
  if (step_us <= 0) {
    ++stats_.out_of_order;
    return false;
  }
  if (static_cast<double>(step_us) > 1.5 * packet_period_us_) {
    const double boundary_gap = ForwardAngle(previous_last_azimuth_rad_, packet.fans[0].azimuth_rad);
    const double packet_sweep = ForwardAngle(packet.fans[0].azimuth_rad,
                                             packet.fans[static_cast<std::size_t>(packet.num_fans - 1)].azimuth_rad);
    if (boundary_gap > 0.5 * packet_sweep && boundary_gap < std::numbers::pi) {
      const auto missing = std::llround(static_cast<double>(step_us) / packet_period_us_) - 1;
      stats_.lost_packets += static_cast<std::uint64_t>(std::max<long long>(missing, 1));
    } else {
      ++stats_.pauses;
    }
  }
  previous_us_past_hour_ = packet.us_past_hour;
  return true;
}

void VelodyneStream::CountError(PacketError error) {
  ++stats_.malformed;
  switch (error) {
    case PacketError::kWrongSize: ++stats_.wrong_size; break;
    case PacketError::kBadBlockFlag: ++stats_.bad_block_flag; break;
    case PacketError::kAzimuthOutOfRange: ++stats_.bad_azimuth; break;
    case PacketError::kUnknownReturnMode: ++stats_.unknown_return_mode; break;
    case PacketError::kNone: break;
  }
}

void VelodyneStream::Emit(const Revolution* revolution) {
  if (revolution == nullptr) return;
  if (revolution->complete) {
    ++stats_.revolutions;
  } else {
    ++stats_.partial_revolutions;
  }
  stats_.dropped_fans += static_cast<std::uint64_t>(revolution->dropped_fans);
  if (handler_) handler_(*revolution);
}

void VelodyneStream::Finish() {
  if (!identification_ && !model_error_ && pending_count_ > 0) DecideModel();
  if (assembler_) Emit(assembler_->Flush());
}

}  // namespace flat2d::hal::velodyne
