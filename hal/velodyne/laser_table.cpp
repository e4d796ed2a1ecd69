#include "hal/velodyne/laser_table.hpp"

#include <cassert>

#include "hal/common/angles.hpp"

namespace flat2d::hal::velodyne {
namespace {

// VLP-16 manual 63-9243 Rev E, Table 9-1: vertical angle (deg) and vertical
// correction (mm) by laser id.
constexpr std::array<double, 16> kVlp16ElevationDeg = {
    -15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
constexpr std::array<double, 16> kVlp16VerticalCorrectionMm = {
    11.2, -0.7, 9.7, -2.2, 8.1, -3.7, 6.6, -5.1, 5.1, -6.6, 3.7, -8.1, 2.2, -9.7, 0.7, -11.2};

// HDL-32E manual 63-9113 Rev M, laser firing order table: elevation (deg) by laser id.
constexpr std::array<double, 32> kHdl32eElevationDeg = {
    -30.67, -9.33, -29.33, -8.00, -28.00, -6.67, -26.67, -5.33,
    -25.33, -4.00, -24.00, -2.67, -22.67, -1.33, -21.33, 0.00,
    -20.00, 1.33,  -18.67, 2.67,  -17.33, 4.00,  -16.00, 5.33,
    -14.67, 6.67,  -13.33, 8.00,  -12.00, 9.33,  -10.67, 10.67};

// VLP-32C manual 63-9325 Rev C, Table 9-1: elevation and azimuth offset (deg) by laser id.
constexpr std::array<double, 32> kVlp32cElevationDeg = {
    -25,    -1,     -1.667, -15.639, -11.31, 0,      -0.667, -8.843,
    -7.254, 0.333,  -0.333, -6.148,  -5.333, 1.333,  0.667,  -4,
    -4.667, 1.667,  1,      -3.667,  -3.333, 3.333,  2.333,  -2.667,
    -3,     7,      4.667,  -2.333,  -2,     15,     10.333, -1.333};
constexpr std::array<double, 32> kVlp32cAzimuthOffsetDeg = {
    1.4, -4.2, 1.4, -1.4, 1.4, -1.4, 4.2, -1.4, 1.4, -4.2, 1.4, -1.4, 4.2, -1.4, 4.2, -1.4,
    1.4, -4.2, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4, 1.4, -1.4, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4};

}  // namespace

double ManualElevationDeg(Model model, int laser_id) {
  assert(laser_id >= 0 && laser_id < LaserCount(model));
  const auto index = static_cast<std::size_t>(laser_id);
  switch (model) {
    case Model::kVlp16: return kVlp16ElevationDeg[index];
    case Model::kHdl32e: return kHdl32eElevationDeg[index];
    case Model::kVlp32c: return kVlp32cElevationDeg[index];
  }
  return 0.0;
}

LaserTable DefaultLaserTable(Model model) {
  LaserTable table;
  table.model = model;
  table.num_lasers = LaserCount(model);
  // VLP-32C distances come in 4 mm units, the others in 2 mm units.
  table.distance_resolution_m = model == Model::kVlp32c ? 0.004 : 0.002;
  for (int id = 0; id < table.num_lasers; ++id) {
    const auto index = static_cast<std::size_t>(id);
    LaserCorrection& laser = table.lasers[index];
    laser.elevation_rad = ManualElevationDeg(model, id) * kDegToRad;
    if (model == Model::kVlp16) {
      laser.vertical_offset_m = kVlp16VerticalCorrectionMm[index] * 1e-3;
    }
    if (model == Model::kVlp32c) {
      laser.rot_correction_rad = -kVlp32cAzimuthOffsetDeg[index] * kDegToRad;
    }
  }
  return table;
}

}  // namespace flat2d::hal::velodyne
