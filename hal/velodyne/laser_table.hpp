// Per-laser geometry of a Velodyne sensor: the factory tables of the user manuals,
// overridable by a calibration file (calibration_yaml.hpp).
//
// Conventions follow the calibration YAML used by the common Velodyne drivers:
// laser_id is the channel's position within a firing sequence; vert_correction is the
// elevation; the firing azimuth of a laser is the block azimuth minus rot_correction
// (so a VLP-32C laser with manual azimuth offset +1.4 deg has rot_correction -1.4 deg);
// dist_correction is added to the measured distance; vert_offset_correction and
// horiz_offset_correction displace the laser's origin.
#pragma once

#include <array>
#include <cstdint>

#include "hal/velodyne/model.hpp"

namespace flat2d::hal::velodyne {

inline constexpr int kMaxLasers = 32;

struct LaserCorrection {
  double elevation_rad = 0.0;         // vert_correction
  double rot_correction_rad = 0.0;    // firing azimuth = block azimuth - rot_correction
  double distance_offset_m = 0.0;     // dist_correction
  double vertical_offset_m = 0.0;     // vert_offset_correction
  double horizontal_offset_m = 0.0;   // horiz_offset_correction
};

struct LaserTable {
  Model model = Model::kVlp16;
  int num_lasers = 16;
  double distance_resolution_m = 0.002;
  std::array<LaserCorrection, kMaxLasers> lasers{};  // indexed by laser_id
};

// The manual's table for a model: elevations, VLP-32C azimuth offsets, VLP-16
// vertical corrections, and the distance resolution (2 mm; 4 mm for the VLP-32C).
LaserTable DefaultLaserTable(Model model);

// Elevation in degrees as printed in the manual's table, by laser id.
double ManualElevationDeg(Model model, int laser_id);

}  // namespace flat2d::hal::velodyne
