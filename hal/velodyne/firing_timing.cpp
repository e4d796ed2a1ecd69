#include "hal/velodyne/firing_timing.hpp"

#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr double kVlp16FiringUs = 2.304;
constexpr double kVlp16SequenceUs = 55.296;
constexpr double kHdl32eFiringUs = 1.152;
constexpr double kHdl32eBlockUs = 46.080;
constexpr double kVlp32cFiringUs = 2.304;
constexpr double kVlp32cBlockUs = 55.296;

}  // namespace

FiringTiming TimingFor(Model model) {
  FiringTiming timing;
  switch (model) {
    case Model::kVlp16:
      timing.fans_per_block = 2;
      timing.lasers_per_fan = 16;
      timing.block_period_us = 2 * kVlp16SequenceUs;
      for (int c = 0; c < 32; ++c) {
        timing.channel_offset_us[static_cast<std::size_t>(c)] =
            (c / 16) * kVlp16SequenceUs + (c % 16) * kVlp16FiringUs;
      }
      break;
    case Model::kHdl32e:
      timing.block_period_us = kHdl32eBlockUs;
      for (int c = 0; c < 32; ++c) {
        timing.channel_offset_us[static_cast<std::size_t>(c)] = (c / 2) * kHdl32eFiringUs;
      }
      break;
    case Model::kVlp32c:
      timing.block_period_us = kVlp32cBlockUs;
      for (int c = 0; c < 32; ++c) {
        timing.channel_offset_us[static_cast<std::size_t>(c)] = (c / 2) * kVlp32cFiringUs;
      }
      break;
  }
  return timing;
}

double PacketPeriodUs(Model model, ReturnMode mode) {
  const double firings = mode == ReturnMode::kDual ? kBlocksPerPacket / 2 : kBlocksPerPacket;
  return firings * TimingFor(model).block_period_us;
}

double PacketsPerSecond(Model model, ReturnMode mode) {
  return 1e6 / PacketPeriodUs(model, mode);
}

}  // namespace flat2d::hal::velodyne
