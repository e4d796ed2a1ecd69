// The DBC of the simulated vehicle (hal/sim/vehicle.dbc), compiled into the library so
// that `flat2d-sim` can write DIR/vehicle.dbc beside DIR/can.log without an installed data
// directory. The build generates the text's definition from the file (hal/sim/CMakeLists.txt);
// the file is also installed to share/flat2d/sim/vehicle.dbc.
//
// Messages (ids decimal as in the file): STEERING 37 (Motorola, Toyota checksum),
// YAW_RATE 176 (Intel, Toyota checksum), WHEEL_SPEEDS 416 (Motorola, Honda checksum);
// each with a 4-bit rolling COUNTER. packaging/config/odometry/flat2d_sim.textproto maps
// them for CanOdometry.
#pragma once

#include <string_view>

#include "hal/can/dbc.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::sim {

inline constexpr std::string_view kWheelSpeedsMessage = "WHEEL_SPEEDS";
inline constexpr std::string_view kYawRateMessage = "YAW_RATE";
inline constexpr std::string_view kSteeringMessage = "STEERING";

// The file's bytes, exactly.
std::string_view VehicleDbcText();

// VehicleDbcText parsed (source name "vehicle.dbc").
Result<can::Dbc> VehicleDbc();

}  // namespace flat2d::hal::sim
