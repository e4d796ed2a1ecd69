// When each channel record of a data packet was fired, from the manuals' timing
// tables (VLP-16 manual 63-9243 Rev E 9.4, HDL-32E 63-9113 Rev M 9.4, VLP-32C
// 63-9325 Rev C 9.4).
//
// VLP-16: a block holds two firing sequences of 16 lasers; lasers fire 2.304 us apart,
// a sequence lasts 55.296 us (16 firings and a recharge), a block 110.592 us.
// HDL-32E: a block is one sequence of 32 lasers fired in pairs 1.152 us apart; 46.080 us
// per block. VLP-32C: a block is one sequence of 32 lasers fired in pairs 2.304 us
// apart; 55.296 us per block. In dual-return mode two consecutive blocks hold the two
// returns of the same firing, so a packet covers half the time.
#pragma once

#include <array>

#include "hal/velodyne/model.hpp"

namespace flat2d::hal::velodyne {

struct FiringTiming {
  int fans_per_block = 1;      // firing sequences (vertical fans) per data block
  int lasers_per_fan = 32;
  double block_period_us = 0;  // time from one block's firing to the next (single return)
  std::array<double, 32> channel_offset_us{};  // firing time of channel c after its block's
};

FiringTiming TimingFor(Model model);

// Time covered by one data packet: 12 blocks, or 6 firings in dual-return mode.
double PacketPeriodUs(Model model, ReturnMode mode);

// Data packets per second the sensor sends (independent of rotation speed).
double PacketsPerSecond(Model model, ReturnMode mode);

}  // namespace flat2d::hal::velodyne
