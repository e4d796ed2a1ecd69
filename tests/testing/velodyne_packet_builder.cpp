#include "tests/testing/velodyne_packet_builder.hpp"

namespace flat2d::testing {
namespace {
constexpr std::size_t kBlockSize = 100;
}  // namespace

DataPacketBuilder::DataPacketBuilder(std::uint8_t return_mode, std::uint8_t product_id,
                                     int first_azimuth, int azimuth_step) {
  for (int block = 0; block < 12; ++block) {
    BlockFlag(block, 0xFF, 0xEE);
    BlockAzimuth(block, ((first_azimuth + block * azimuth_step) % 36000 + 36000) % 36000);
  }
  FactoryBytes(return_mode, product_id);
}

DataPacketBuilder& DataPacketBuilder::BlockAzimuth(int block, int azimuth_units) {
  Put16(static_cast<std::size_t>(block) * kBlockSize + 2, static_cast<std::uint16_t>(azimuth_units));
  return *this;
}

DataPacketBuilder& DataPacketBuilder::BlockFlag(int block, std::uint8_t first, std::uint8_t second) {
  bytes_[static_cast<std::size_t>(block) * kBlockSize] = first;
  bytes_[static_cast<std::size_t>(block) * kBlockSize + 1] = second;
  return *this;
}

DataPacketBuilder& DataPacketBuilder::Record(int block, int channel, std::uint16_t distance,
                                             std::uint8_t intensity) {
  const std::size_t offset = static_cast<std::size_t>(block) * kBlockSize + 4 +
                             static_cast<std::size_t>(channel) * 3;
  Put16(offset, distance);
  bytes_[offset + 2] = intensity;
  return *this;
}

DataPacketBuilder& DataPacketBuilder::Timestamp(std::uint32_t us_past_hour) {
  for (std::size_t i = 0; i < 4; ++i) {
    bytes_[1200 + i] = static_cast<std::uint8_t>(us_past_hour >> (8 * i));
  }
  return *this;
}

DataPacketBuilder& DataPacketBuilder::FactoryBytes(std::uint8_t return_mode, std::uint8_t product_id) {
  bytes_[1204] = return_mode;
  bytes_[1205] = product_id;
  return *this;
}

void AdvanceDeviceTime(std::span<std::uint8_t> payload, std::uint32_t by_us) {
  std::size_t offset = 0;
  if (payload.size() == 1206) {
    offset = 1200;
  } else if (payload.size() == 512) {
    offset = 198;
  } else {
    return;
  }
  std::uint32_t now = 0;
  for (std::size_t i = 0; i < 4; ++i) now |= static_cast<std::uint32_t>(payload[offset + i]) << (8 * i);
  now = static_cast<std::uint32_t>((static_cast<std::uint64_t>(now) + by_us) % 3'600'000'000u);
  for (std::size_t i = 0; i < 4; ++i) payload[offset + i] = static_cast<std::uint8_t>(now >> (8 * i));
}

void DataPacketBuilder::Put16(std::size_t offset, std::uint16_t value) {
  bytes_[offset] = static_cast<std::uint8_t>(value & 0xFF);
  bytes_[offset + 1] = static_cast<std::uint8_t>(value >> 8);
}

}  // namespace flat2d::testing
