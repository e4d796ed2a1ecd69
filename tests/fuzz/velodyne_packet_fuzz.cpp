// Fuzzes the data-packet decoder directly: the first byte picks the model, the rest is
// the payload (any length, so the size check is exercised too). Afterwards every
// decoded return must be finite and lie within its laser's maximum distance.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "hal/velodyne/packet_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace flat2d::hal::velodyne;
  if (size == 0) return 0;
  static PacketDecoder decoders[] = {PacketDecoder(DefaultLaserTable(Model::kVlp16)),
                                     PacketDecoder(DefaultLaserTable(Model::kHdl32e)),
                                     PacketDecoder(DefaultLaserTable(Model::kVlp32c))};
  static DecodedPacket packet;
  PacketDecoder& decoder = decoders[data[0] % 3];
  decoder.Decode(std::span(data + 1, size - 1), packet);
  for (int f = 0; f < packet.num_fans; ++f) {
    for (const LaserReturn& r : packet.fans[static_cast<std::size_t>(f)].returns) {
      if (!std::isfinite(r.xyz.squaredNorm()) || r.range_m > 263.0f) std::abort();
    }
  }
  return 0;
}
