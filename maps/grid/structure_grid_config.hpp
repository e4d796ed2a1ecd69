// Loading and checking StructureGridOptions (structure_grid_options.proto): the text file,
// every required field and range checked with a message naming the field, and the sensor
// mounting as a transform.
#pragma once

#include <filesystem>
#include <span>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "maps/grid/structure_grid_options.pb.h"

namespace flat2d::maps {

// Every problem of `options`, e.g. "slope.hazard_slope_deg: must be in (0, 90)"; ok when none.
Status ValidateStructureGridOptions(const StructureGridOptions& options);

// Parses a text-format file and validates it; errors carry file:line:column or the field.
Result<StructureGridOptions> LoadStructureGridOptions(const std::filesystem::path& path);

// vehicle_T_sensor from the mounting (Z-Y-X Euler angles).
Eigen::Isometry3d VehicleFromSensor(const SensorMounting& mounting);
// ... from its six numbers x, y, z (m), roll, pitch, yaw (deg), as the tools' X,Y,Z,ROLL,PITCH,YAW.
Eigen::Isometry3d VehicleFromSensor(std::span<const double, 6> xyz_roll_pitch_yaw);
// Its inverse: the mounting (Z-Y-X Euler angles, pitch within +-90 deg) of vehicle_T_sensor.
SensorMounting MountingOf(const Eigen::Isometry3d& vehicle_T_sensor);

}  // namespace flat2d::maps
