// Builds Velodyne data packets byte by byte for tests: every field at the offset the
// manuals give, so decoder tests check the decoder against the layout, not itself.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace flat2d::testing {

class DataPacketBuilder {
 public:
  // Blocks get the 0xFFEE flag and azimuths first_azimuth + b * step (hundredths of a
  // degree, wrapped); every distance is 0 (no return).
  DataPacketBuilder(std::uint8_t return_mode, std::uint8_t product_id,
                    int first_azimuth = 0, int azimuth_step = 40);

  DataPacketBuilder& BlockAzimuth(int block, int azimuth_units);
  DataPacketBuilder& BlockFlag(int block, std::uint8_t first, std::uint8_t second);
  DataPacketBuilder& Record(int block, int channel, std::uint16_t distance, std::uint8_t intensity);
  DataPacketBuilder& Timestamp(std::uint32_t us_past_hour);
  DataPacketBuilder& FactoryBytes(std::uint8_t return_mode, std::uint8_t product_id);

  std::span<const std::uint8_t> bytes() const { return bytes_; }
  const std::array<std::uint8_t, 1206>& array() const { return bytes_; }

 private:
  void Put16(std::size_t offset, std::uint16_t value);
  std::array<std::uint8_t, 1206> bytes_{};
};

// Moves the device timestamp of a data (1206-byte) or position (512-byte) payload on by
// `by_us`, wrapping at the hour: replaying a short capture in laps without the laps looking
// like jumps back in time. Other sizes are left alone.
void AdvanceDeviceTime(std::span<std::uint8_t> payload, std::uint32_t by_us);

}  // namespace flat2d::testing
