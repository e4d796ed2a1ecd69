#include "hal/velodyne/firing_schedule.hpp"

namespace flat2d::hal::velodyne {

FiringSchedule::FiringSchedule(Model model, ReturnMode mode) {
  const FiringTiming timing = TimingFor(model);
  const bool dual = mode == ReturnMode::kDual;
  const int blocks = static_cast<int>(kBlocksPerPacket);
  firings_per_packet_ = dual ? blocks / 2 : blocks;
  fans_per_block_ = timing.fans_per_block;
  block_period_us_ = timing.block_period_us;
  const int fan_stride = dual ? 2 : 1;
  for (int block = 0; block < static_cast<int>(kBlocksPerPacket); ++block) {
    const int firing = FiringOfBlock(block);
    const int first_fan = dual ? firing * fans_per_block_ * 2 + block % 2 : block * fans_per_block_;
    kinds_[static_cast<std::size_t>(block)] =
        (dual && block % 2 == 0) || mode == ReturnMode::kLast ? ReturnKind::kLast
                                                               : ReturnKind::kStrongest;
    for (int c = 0; c < static_cast<int>(kChannelsPerBlock); ++c) {
      ChannelFiring& f = firings_[static_cast<std::size_t>(block)][static_cast<std::size_t>(c)];
      f.time_offset_us = firing * timing.block_period_us +
                         timing.channel_offset_us[static_cast<std::size_t>(c)];
      f.fan = first_fan + (c / timing.lasers_per_fan) * fan_stride;
      f.laser_id = c % timing.lasers_per_fan;
    }
  }
}

}  // namespace flat2d::hal::velodyne
