// The order in which a fan's lasers point, bottom-up: the slope classifier (thesis 7.1.3)
// walks a fan from the lowest beam to the highest, but a Velodyne numbers its lasers in
// firing order (the HDL-32E interleaves upper and lower blocks), so the order comes from
// the laser table's elevations.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>

#include "hal/velodyne/laser_table.hpp"

namespace flat2d::maps {

struct LaserOrder {
  int count = 0;
  std::array<std::uint8_t, hal::velodyne::kMaxLasers> bottom_up{};  // laser ids, lowest beam first
};

inline LaserOrder BottomUpOrder(const hal::velodyne::LaserTable& table) {
  LaserOrder order;
  order.count = table.num_lasers;
  std::iota(order.bottom_up.begin(), order.bottom_up.begin() + order.count, std::uint8_t{0});
  std::stable_sort(order.bottom_up.begin(), order.bottom_up.begin() + order.count,
                   [&](std::uint8_t a, std::uint8_t b) {
                     return table.lasers[a].elevation_rad < table.lasers[b].elevation_rad;
                   });
  return order;
}

}  // namespace flat2d::maps
