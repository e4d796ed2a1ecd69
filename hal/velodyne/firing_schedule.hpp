// Where and when every channel record of a data packet was fired, as one table for a
// model and return mode: the decoder places records by it and the encoder (simulator)
// schedules firings by it, so the two cannot disagree.
//
// From firing_timing.hpp (the manuals' 9.4 tables): a block's firing index is the block,
// or block / 2 in dual-return mode, where blocks 2k and 2k+1 hold the last and the
// strongest return of firing k; fans are numbered in time order, the two returns of a
// firing interleaved, so fan stamps never decrease.
#pragma once

#include <array>

#include "hal/velodyne/fan.hpp"
#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/model.hpp"
#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::velodyne {

// Where and when the decoder places one channel record.
struct ChannelFiring {
  double time_offset_us = 0.0;  // firing time after the packet timestamp
  int fan = 0;                  // index into DecodedPacket::fans
  int laser_id = 0;             // index into Fan::returns and LaserTable::lasers
};

// For one model and return mode, the firing of every (block, channel) as PacketDecoder
// assumes it: in dual-return mode blocks 2k and 2k+1 hold the last and the strongest return
// of firing k.
class FiringSchedule {
 public:
  FiringSchedule(Model model, ReturnMode mode);

  const ChannelFiring& At(int block, int channel) const {
    return firings_[static_cast<std::size_t>(block)][static_cast<std::size_t>(channel)];
  }
  ReturnKind KindOfBlock(int block) const { return kinds_[static_cast<std::size_t>(block)]; }
  // Firings per packet: 12, or 6 in dual-return mode (consecutive blocks share a firing).
  int firings() const { return firings_per_packet_; }
  // Firing index (0..firings()-1) of a block: the block azimuth is the azimuth of it.
  int FiringOfBlock(int block) const { return firings_per_packet_ == 12 ? block : block / 2; }
  int fans_per_block() const { return fans_per_block_; }
  double block_period_us() const { return block_period_us_; }

 private:
  std::array<std::array<ChannelFiring, kChannelsPerBlock>, kBlocksPerPacket> firings_{};
  std::array<ReturnKind, kBlocksPerPacket> kinds_{};
  int firings_per_packet_ = 12;
  int fans_per_block_ = 1;
  double block_period_us_ = 0.0;
};

}  // namespace flat2d::hal::velodyne
