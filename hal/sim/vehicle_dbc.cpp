#include "hal/sim/vehicle_dbc.hpp"

namespace flat2d::hal::sim {

Result<can::Dbc> VehicleDbc() { return can::ParseDbc(VehicleDbcText(), "vehicle.dbc"); }

}  // namespace flat2d::hal::sim
