// A vertical fan: one firing sequence of all lasers at (nearly) one azimuth, the unit
// that the structure-grid classifier consumes (thesis 7.1.3 processes "each vertical
// fan bottom-up").
//
// Frames: the sensor frame is x forward, y left, z up (metres). Azimuths are the
// Velodyne's own: clockwise from x seen from above, in [0, 2 pi).
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "hal/common/time.hpp"
#include "hal/velodyne/laser_table.hpp"

namespace flat2d::hal::velodyne {

// Which return of a firing a fan holds. Single-return packets hold kStrongest or
// kLast; dual-return packets hold a kLast fan and a kStrongest fan per firing (the
// second strongest if the strongest is also the last).
enum class ReturnKind : std::uint8_t { kStrongest, kLast };

struct LaserReturn {
  Eigen::Vector3f xyz = Eigen::Vector3f::Zero();  // sensor frame; zero when no return
  float range_m = 0.0f;              // corrected distance; 0 = no return
  float azimuth_rad = 0.0f;          // this laser's interpolated firing azimuth
  std::uint16_t time_offset_ns = 0;  // firing time after the fan's stamp (< 56 us)
  std::uint8_t intensity = 0;        // calibrated reflectivity, 0..255
};

struct Fan {
  TimeNs stamp_ns = 0;        // firing time of the fan's first laser
  float azimuth_rad = 0.0f;   // fan azimuth before per-laser offsets
  ReturnKind kind = ReturnKind::kStrongest;
  std::uint8_t num_lasers = 0;
  std::uint8_t num_points = 0;  // returns with a non-zero range, counted by the decoder
  std::array<LaserReturn, kMaxLasers> returns{};  // indexed by laser id
};

}  // namespace flat2d::hal::velodyne
